// ptnet har-bench end to end: a small procedural benchmark writes its
// outputs; bad input is one line on stderr, exit status 1, nothing written.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;
using ptnet::testing_cli::run_ptnet;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("ptnet_har_bench_smoke_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

const std::string kBase =
    "har-bench --performers 2 --seconds 8 --recorded-bodies 2 --bodies-per-band 1 --runs 1 --ensemble 1 --epochs 1";
const std::string kSmall = kBase + " --syntheses copy";

}  // namespace

TEST(HarBenchCli, WritesResultsAndRefusesToOverwriteThem) {
  const fs::path dir = scratch("run");
  const std::string out = (dir / "hb").string();
  auto r = run_ptnet(kSmall + " --out " + out, dir / "log");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"results.json", "index.html", "f1.svg"}) EXPECT_TRUE(fs::exists(fs::path(out) / f)) << f;
  EXPECT_NE(r.out.find("oracle"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Time:"), std::string::npos) << r.out;
  const auto before = fs::last_write_time(fs::path(out) / "results.json");
  r = run_ptnet(kSmall + " --out " + out, dir / "log");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("results.json: exists; pass --force to overwrite"), std::string::npos) << r.err;
  EXPECT_EQ(fs::last_write_time(fs::path(out) / "results.json"), before);
  fs::remove_all(dir);
}

TEST(HarBenchCli, BadInputIsOneLineAndNoOutput) {
  const fs::path dir = scratch("bad");
  const std::string out = (dir / "hb").string();
  auto r = run_ptnet(kSmall + " --deployment-bands giant --out " + out, dir / "log");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("unknown body band 'giant'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(fs::path(out) / "results.json"));
  r = run_ptnet(kBase + " --syntheses model --out " + out, dir / "log");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("needs a transfer model"), std::string::npos) << r.err;
  r = run_ptnet(kSmall + " --activities swimming --out " + out, dir / "log");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no clip of activity 'swimming'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // The training set: written once, then not overwritten without --force.
  const std::string ts = (dir / "t.h5").string();
  r = run_ptnet("har-bench --performers 2 --seconds 8 --write-training-set " + ts + " --training-bodies 2", dir / "log");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_ptnet("har-bench --performers 2 --seconds 8 --write-training-set " + ts + " --training-bodies 2", dir / "log");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(ts), std::string::npos) << r.err;
  fs::remove_all(dir);
}
