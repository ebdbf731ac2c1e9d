// The gait-lab commands on the committed synthetic trial (tests/data/gait,
// scripts/make-gait-trial.py), so that they run in a clone without
// ../shared: `ptnet info` reads the marker file with its static trial,
// `ptnet physics-bench` writes its page, table and force files from the
// trials CSV and refuses to overwrite them. The figures themselves are
// checked in plates_gait_trial_test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_util.hpp"

namespace {

namespace fs = std::filesystem;
using ptnet::testing_cli::RunResult;
using ptnet::testing_cli::slurp;

const std::string kGait = std::string(PTNET_TEST_DATA) + "/gait";

struct Dir {
  fs::path path = fs::temp_directory_path() / ("ptnet_gait_trial_cli_" + std::to_string(::getpid()));
  Dir() { fs::create_directories(path); }
  ~Dir() { fs::remove_all(path); }
  RunResult run(const std::string& args) const { return ptnet::testing_cli::run_ptnet(args, path / "run", path); }
};

}  // namespace

TEST(CliGaitTrial, InfoReadsTheMarkerFileWithItsStaticTrial) {
  Dir d;
  const RunResult r = d.run("info '" + kGait + "/walk.trc' --static '" + kGait + "/walk_static.trc' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "trc");
  EXPECT_EQ(j["marker_map"], "delaware");
  EXPECT_EQ(j["frames"], 151);
  EXPECT_NEAR(j["treadmill_belt_mps"].get<double>(), 1.10, 1.10 * 0.05);  // the trial's belt
}

TEST(CliGaitTrial, PhysicsBenchWritesThePageAndRefusesToOverwrite) {
  Dir d;
  const std::string args = "physics-bench --trials '" + kGait + "/trials.csv' --out phys";
  const RunResult r = d.run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("walk       simulated"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("walk       naive"), std::string::npos) << r.out;
  for (const char* f : {"index.html", "results.json", "walk_sim.mot", "walk_frames.csv", "walk_total.svg", "walk_feet.svg", "walk_cop.svg"})
    EXPECT_TRUE(fs::exists(d.path / "phys" / f)) << f;
  const nlohmann::json j = nlohmann::json::parse(slurp(d.path / "phys" / "results.json"));
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["coverage"], "all");
  EXPECT_EQ(j[0]["compared_frames"], 151);
  EXPECT_LT(j[0]["simulated"]["rmse_bw"].get<double>(), j[0]["naive"]["rmse_bw"].get<double>());
  const RunResult again = d.run(args);
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("exists; pass --force"), std::string::npos) << again.err;
  EXPECT_EQ(d.run(args + " --force").status, 0);
}
