// The gait-lab commands end to end: `ptnet simulate --forces` writes each
// sequence's ground reaction and refuses to overwrite it; `ptnet forces`
// reads the same reaction off an ideal mat; `ptnet
// physics-bench` on the real trials (skipped without ../shared/real-gait)
// writes its page, table and force files, refuses to overwrite them, and a
// bad trials CSV is one line; `ptnet info`, `ptnet simulate` and `ptnet
// motions --from` read a .trc.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "core/csv.hpp"

namespace {

namespace fs = std::filesystem;
using ptnet::testing_cli::RunResult;
using ptnet::testing_cli::slurp;

struct Dir {
  fs::path path = fs::temp_directory_path() / ("ptnet_physics_cli_" + std::to_string(::getpid()));
  Dir() { fs::create_directories(path); }
  ~Dir() { fs::remove_all(path); }
  RunResult run(const std::string& args) const { return ptnet::testing_cli::run_ptnet(args, path / "run", path); }
};

const std::string kGait = PTNET_SHARED_GAIT;

}  // namespace

TEST(CliForces, SimulateWritesEachSequencesGroundReaction) {
  Dir d;
  std::ofstream(d.path / "b.csv") << "id,sex,height_cm,weight_kg\nb1,female,160,55\n";
  const std::string args = "simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies b.csv --out e.h5 "
                           "--forces f --quiet";
  const RunResult r = d.run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  int files = 0;
  for (const auto& e : fs::directory_iterator(d.path / "f")) {
    ++files;
    EXPECT_EQ(e.path().extension(), ".mot");
    const std::string mot = slurp(e.path());
    EXPECT_NE(mot.find("endheader\ntime\ttotal_force_vy\ttotal_force_bw\tl_ground_force_vy"), std::string::npos);
  }
  EXPECT_EQ(files, 4);  // one clip per category
  // Again: the dataset and the force files exist.
  const RunResult again = d.run(args);
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("exists; pass --force to overwrite"), std::string::npos) << again.err;
  EXPECT_EQ(d.run(args + " --force --forces-format csv").status, 0);
  EXPECT_TRUE(fs::exists(d.path / "f" / "p1_walking_t1__b1.csv"));
}

// `ptnet forces` reads a dataset's mat as a force plate: on the procedural
// motions (always on the mat) with an ideal sensor it finds the simulator's
// own ground reaction in every frame (Newton: the mat carries the body), and
// it refuses to overwrite its files or to read a sequence that is not there.
TEST(CliForces, TheMatReadsTheSimulatorsGroundReaction) {
  Dir d;
  std::ofstream(d.path / "b.csv") << "id,sex,height_cm,weight_kg\nb1,male,185,90\n";
  ASSERT_EQ(d.run("simulate --embedded --performers 1 --takes 1 --seconds 3 --bodies b.csv --out e.h5 --ideal-sensor "
                  "--forces sim --forces-format csv --quiet")
                .status,
            0);
  const RunResult r = d.run("forces e.h5 --out mat --format csv");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("forces: wrote 4 files to mat"), std::string::npos) << r.err;
  const auto column = [](const fs::path& csv, const std::string& name) {
    const ptnet::CsvTable t = ptnet::parse_csv(slurp(csv), csv.string());
    const int at = t.required(name, name);
    std::vector<double> out;
    for (const auto& row : t.rows) out.push_back(std::stod(row.fields[std::size_t(at)]));
    return out;
  };
  for (const char* motion : {"p1_walking_t1__b1", "p1_freestyle_t1__b1"}) {
    SCOPED_TRACE(motion);
    const auto mat = column(d.path / "mat" / (std::string(motion) + ".csv"), "ground_force_vy");
    const auto sim = column(d.path / "sim" / (std::string(motion) + ".csv"), "total_force_vy");
    ASSERT_EQ(mat.size(), sim.size());
    ASSERT_EQ(mat.size(), 90u);
    double mean_bw = 0;
    // The mat stores each cell as float32 (relative rounding <= 2^-24 = 6e-8
    // per cell, so <= 6e-8 of a sum of positive cells) and the CSV prints 9
    // digits (5e-9): 1e-5 of body weight is over 100 x what rounding allows.
    for (std::size_t t = 0; t < mat.size(); ++t) {
      EXPECT_NEAR(mat[t], sim[t], 1e-5 * 90 * 9.81) << t;
      mean_bw += mat[t] / (90 * 9.81) / double(mat.size());
    }
    EXPECT_NEAR(mean_bw, 1.0, 0.05);  // over 3 s the body neither rises nor falls much
  }
  const RunResult again = d.run("forces e.h5 --out mat --format csv -s p1_rom_t1__b1");
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("exists; pass --force to overwrite"), std::string::npos) << again.err;
  const RunResult absent = d.run("forces e.h5 --out m2 -s nope");
  EXPECT_EQ(absent.status, 1);
  EXPECT_NE(absent.err.find("e.h5: no sequence 'nope'"), std::string::npos) << absent.err;
  EXPECT_FALSE(fs::exists(d.path / "m2"));
}

TEST(CliPhysicsBench, RealTrialsGiveThePageAndRefuseToOverwrite) {
  if (!fs::exists(kGait + "/walk_s01.trc")) GTEST_SKIP() << "../shared/real-gait not found";
  Dir d;
  const std::string args = "physics-bench --trials '" + std::string(PTNET_SOURCE_DIR) + "/bench/real-gait.csv' --data '" +
                           kGait + "' --out phys";
  const RunResult r = d.run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("walk_s01   simulated"), std::string::npos) << r.out;
  for (const char* f : {"index.html", "results.json", "walk_s01_sim.mot", "run_s02_frames.csv", "run_s02_total.svg"})
    EXPECT_TRUE(fs::exists(d.path / "phys" / f)) << f;
  const nlohmann::json j = nlohmann::json::parse(slurp(d.path / "phys" / "results.json"));
  ASSERT_EQ(j.size(), 8u);  // two OpenSim trials, six of OpenCap subject 4
  for (const auto& t : j) EXPECT_LT(t["simulated"]["rmse_bw"].get<double>(), t["naive"]["rmse_bw"].get<double>()) << t["trial"];
  EXPECT_TRUE(fs::exists(d.path / "phys" / "os4_STS1_cop.svg"));
  const RunResult again = d.run(args);
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("exists; pass --force"), std::string::npos) << again.err;
  // A trials CSV without a column it needs.
  std::ofstream(d.path / "bad.csv") << "trial,markers\nx,x.trc\n";
  const RunResult bad = d.run("physics-bench --trials bad.csv --out p2");
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(bad.err.rfind("ptnet: error: bad.csv:1: expected a header with column plates", 0), 0u) << bad.err;
  EXPECT_EQ(bad.err.find('\n'), bad.err.size() - 1);
  EXPECT_FALSE(fs::exists(d.path / "p2"));
}

TEST(CliMarkers, InfoAndSimulateReadATrc) {
  if (!fs::exists(kGait + "/run_s02.trc")) GTEST_SKIP() << "../shared/real-gait not found";
  Dir d;
  const RunResult info = d.run("info '" + kGait + "/run_s02.trc' --static '" + kGait + "/run_s02_static.trc' --json");
  ASSERT_EQ(info.status, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["format"], "trc");
  EXPECT_EQ(j["marker_map"], "delaware");
  EXPECT_GT(j["treadmill_belt_mps"].get<double>(), 3.5);
  std::ofstream(d.path / "s.csv") << "id,sex,height_cm,weight_kg,role\ns02,male,183,65.9,original\n";
  std::ofstream(d.path / "c.csv") << "file,subject,category,take,static\n" << kGait << "/run_s02.trc,s02,walking,1,"
                                  << kGait << "/run_s02_static.trc\n";
  const RunResult sim = d.run("simulate --clips c.csv --bodies s.csv --out r.h5 --placement follow");
  EXPECT_EQ(sim.status, 0) << sim.err;
  EXPECT_TRUE(fs::exists(d.path / "r.h5"));
  // The trial's canonical joints as BVH, read back.
  ASSERT_EQ(d.run("motions --from '" + kGait + "/run_s02.trc' --static '" + kGait + "/run_s02_static.trc' --out r.bvh")
                .status,
            0);
  const RunResult bvh = d.run("info r.bvh --json");
  ASSERT_EQ(bvh.status, 0) << bvh.err;
  EXPECT_EQ(nlohmann::json::parse(bvh.out)["frames"], 300);  // 10 s at 30 fps
  // A marker map that cannot place the file: one line, no output.
  std::ofstream(d.path / "m.map") << "r_asis = NOPE\n";
  const RunResult bad = d.run("info '" + kGait + "/run_s02.trc' --marker-map m.map");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("marker map 'm' cannot place the markers: it lacks r_asis (NOPE)"), std::string::npos) << bad.err;
  EXPECT_EQ(bad.err.find('\n'), bad.err.size() - 1);
}
