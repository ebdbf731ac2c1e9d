// ptnet motions end to end: writes a BVH that ptnet reads back on the
// canonical skeleton, refuses to overwrite without --force (exit 1), usage
// errors exit 2, and set mode writes one clip per performer x category x
// take plus clips.csv.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ptnet/motion.hpp"

namespace fs = std::filesystem;

namespace {

struct RunResult {
  int code;
  std::string err;
};

RunResult run(const std::string& args, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string cmd = "cd '" + dir.string() + "' && '" + std::string(PTNET_BINARY) + "' " + args + " 2> '" +
                          err.string() + "' > /dev/null";
  const int status = std::system(cmd.c_str());
  std::ifstream in(err);
  std::stringstream s;
  s << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, s.str()};
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class CliMotions : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ptnet_cli_motions_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(CliMotions, WritesAClipAndRefusesToOverwriteWithoutForce) {
  RunResult r = run("motions --category walking --performer 2 --take 1 --seconds 3 --out walk.bvh", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("walk.bvh"), std::string::npos);  // progress on stderr
  const ptnet::Motion m = ptnet::load_motion((dir_ / "walk.bvh").string(), ptnet::MotionOptions{});
  EXPECT_EQ(m.size(), 90);
  EXPECT_NEAR(ptnet::standing_height(m), ptnet::performer_height_cm(2) / 100, 0.06 * ptnet::performer_height_cm(2) / 100);

  const std::string before = slurp(dir_ / "walk.bvh");
  r = run("motions --category rom --seconds 2 --out walk.bvh", dir_);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, "ptnet: error: walk.bvh: exists; pass --force to overwrite\n");
  EXPECT_EQ(slurp(dir_ / "walk.bvh"), before);
  r = run("-q motions --category rom --seconds 2 --out walk.bvh --force", dir_);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // --quiet
  EXPECT_NE(slurp(dir_ / "walk.bvh"), before);
}

TEST_F(CliMotions, UsageErrorsExitTwo) {
  EXPECT_EQ(run("motions --seconds 2", dir_).code, 2);                    // no --out / --out-dir
  EXPECT_EQ(run("motions --out a.bvh", dir_).code, 2);                    // --out needs --category
  EXPECT_EQ(run("motions --category jogging --out a.bvh", dir_).code, 2);  // unknown category
  EXPECT_EQ(run("motions --category rom --out a.bvh --out-dir d", dir_).code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "a.bvh"));
}

// A category twice would write its clips twice: refused
// before any clip.
TEST_F(CliMotions, ACategoryTwiceIsRefused) {
  const RunResult r = run("motions --performers 1 --categories walking,acting,walking --seconds 2 --out-dir twice", dir_);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(r.err, "ptnet: error: --categories: walking given twice\n");
  EXPECT_FALSE(fs::exists(dir_ / "twice" / "clips.csv"));
}

TEST_F(CliMotions, SetModeWritesEveryClipAndAManifest) {
  const RunResult r = run("motions --performers 2 --takes 2 --categories walking,acting --seconds 2 --out-dir set", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "set" / "clips.csv"),
            "file,subject,category,take\n"
            "p1_walking_t1.bvh,1,walking,1\np1_walking_t2.bvh,1,walking,2\n"
            "p1_acting_t1.bvh,1,acting,1\np1_acting_t2.bvh,1,acting,2\n"
            "p2_walking_t1.bvh,2,walking,1\np2_walking_t2.bvh,2,walking,2\n"
            "p2_acting_t1.bvh,2,acting,1\np2_acting_t2.bvh,2,acting,2\n");
  for (const char* f : {"p1_walking_t1.bvh", "p2_acting_t2.bvh"})
    EXPECT_EQ(ptnet::read_bvh((dir_ / "set" / f).string()).frames(), 60) << f;
  // Takes differ, the same clip again is identical.
  EXPECT_NE(slurp(dir_ / "set" / "p1_walking_t1.bvh"), slurp(dir_ / "set" / "p1_walking_t2.bvh"));
  ASSERT_EQ(run("motions --category walking --performer 1 --take 1 --seconds 2 --out again.bvh", dir_).code, 0);
  EXPECT_EQ(slurp(dir_ / "again.bvh"), slurp(dir_ / "set" / "p1_walking_t1.bvh"));
  // A second run refuses (exit 1) and leaves the folder as it was.
  const RunResult again = run("motions --performers 1 --seconds 2 --out-dir set", dir_);
  EXPECT_EQ(again.code, 1);
  EXPECT_NE(again.err.find("exists; pass --force to overwrite"), std::string::npos);
}

}  // namespace
