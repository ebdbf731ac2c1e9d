// `ptnet info` end to end: every malformed fixture exits 1 with exactly one
// line on stderr, "ptnet: error: <file>:...", and no crash; a good file
// exits 0 and --json parses.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;

namespace {

using ptnet::testing_cli::RunResult;
using ptnet::testing_cli::slurp;

RunResult run(const std::string& args) {
  return ptnet::testing_cli::run_ptnet(
      args, fs::temp_directory_path() / ("ptnet_info_smoke_" + std::to_string(::getpid())));
}

}  // namespace

TEST(CliInfo, EveryMalformedFixtureIsOneLineAndExitOne) {
  const fs::path dir = fs::path(PTNET_TEST_DATA) / "malformed";
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(dir)) paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  ASSERT_GE(paths.size(), 12u);
  // The binary takes ~1 s to start (LibTorch): run all fixtures at once.
  const fs::path tmp =
      fs::temp_directory_path() / ("ptnet_info_malformed_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  std::string script;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const std::string base = (tmp / std::to_string(i)).string();
    script += "('" + std::string(PTNET_BINARY) + "' info '" + paths[i] + "' >'" + base +
              ".out' 2>'" + base + ".err'; echo $? >'" + base + ".rc') &\n";
  }
  script += "wait\n";
  std::ofstream(tmp / "run.sh") << script;
  ASSERT_EQ(std::system(("sh '" + (tmp / "run.sh").string() + "'").c_str()), 0);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const std::string& path = paths[i];
    SCOPED_TRACE(path);
    const std::string out = slurp(tmp / (std::to_string(i) + ".out"));
    const std::string err = slurp(tmp / (std::to_string(i) + ".err"));
    EXPECT_EQ(slurp(tmp / (std::to_string(i) + ".rc")), "1\n");
    EXPECT_TRUE(out.empty()) << out;
    ASSERT_FALSE(err.empty());
    EXPECT_EQ(err.find('\n'), err.size() - 1) << err;  // exactly one line
    EXPECT_EQ(err.rfind("ptnet: error: " + path + ":", 0), 0u) << err;
    EXPECT_NE(err.find(": expected "), std::string::npos) << err;
  }
  fs::remove_all(tmp);
}

TEST(CliInfo, GoodFileTextAndJson) {
  const std::string good = std::string(PTNET_TEST_DATA) + "/bvh/tpose_cmu_small.bvh";
  const RunResult text = run("info '" + good + "'");
  EXPECT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("standing height   1.700 m"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("frame 0 is a T-pose, dropped"), std::string::npos) << text.out;

  const RunResult js = run("info --json '" + good + "'");
  ASSERT_EQ(js.status, 0) << js.err;
  const nlohmann::json j = nlohmann::json::parse(js.out);
  EXPECT_EQ(j["format"], "bvh");
  EXPECT_EQ(j["joints"], 21);
  EXPECT_EQ(j["frames"], 4);
  EXPECT_EQ(j["units"], "cm");
  EXPECT_NEAR(j["fps"].get<double>(), 30.0, 1e-3);
  EXPECT_NEAR(j["standing_height_m"].get<double>(), 1.70, 1e-3);
  EXPECT_NEAR(j["duration_s"].get<double>(), 0.1, 1e-4);  // 3 frames after the T-pose
  EXPECT_EQ(j["tpose_dropped"], true);
  EXPECT_EQ(j["canonical"]["left_shoulder"], "LeftArm");
  EXPECT_EQ(j["canonical"]["chest"], "Spine1");

  const RunResult keep = run("info --json --keep-tpose --units m '" + good + "'");
  ASSERT_EQ(keep.status, 0) << keep.err;
  const nlohmann::json k = nlohmann::json::parse(keep.out);
  EXPECT_EQ(k["units"], "m");
  EXPECT_EQ(k["tpose_dropped"], false);
}

TEST(CliInfo, OtherProblemsAreOneLineErrors) {
  const RunResult missing = run("info /nonexistent/walk.bvh");
  EXPECT_EQ(missing.status, 1);
  EXPECT_EQ(missing.err, "ptnet: error: /nonexistent/walk.bvh: no such file\n");
  const RunResult h5 = run("info /nonexistent/data.h5");
  EXPECT_EQ(h5.status, 1);
  EXPECT_EQ(h5.err, "ptnet: error: /nonexistent/data.h5: no such file\n");
  const RunResult other = run("info notes.txt");
  EXPECT_EQ(other.status, 1);
  EXPECT_NE(other.err.find("unsupported file type '.txt'"), std::string::npos) << other.err;
  const RunResult usage = run("info");
  EXPECT_EQ(usage.status, 2);
  const RunResult units = run("info --units furlong x.bvh");
  EXPECT_EQ(units.status, 2);
}
