// `ptnet simulate --shard K/N` and `ptnet merge` through the real binary:
// two shards merged give the unsharded file's sequences (`ptnet info --json`
// of both is the same but for the file name); bad --shard values and an
// existing --out are one-line errors that leave no file behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;
using ptnet::testing_cli::run_ptnet;
using ptnet::testing_cli::slurp;

namespace {

class ShardCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ptnet_shard_smoke_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "bodies.csv") << "id,sex,height_cm,weight_kg,role\nf1,female,160,58,retargeted\n"
                                          "m1,male,185,86,original\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  ptnet::testing_cli::RunResult ptnet(const std::string& args) { return run_ptnet(args, dir_ / "run", dir_); }
  fs::path dir_;
};

const std::string kSimulate = "simulate --embedded --performers 1 --takes 1 --seconds 1 --bodies bodies.csv --threads 2";

// `ptnet info --json` without the line naming the file.
std::string info_without_name(ptnet::testing_cli::RunResult r, const std::string& name) {
  for (std::size_t at = r.out.find(name); at != std::string::npos; at = r.out.find(name))
    r.out.erase(at, name.size());
  return r.out;
}

}  // namespace

TEST_F(ShardCli, MergedShardsDescribeAsTheWhole) {
  ASSERT_EQ(ptnet(kSimulate + " --out whole.h5").status, 0);
  ASSERT_EQ(ptnet(kSimulate + " --shard 0/2 --out a.h5").status, 0);
  ASSERT_EQ(ptnet(kSimulate + " --shard 1/2 --out b.h5").status, 0);
  auto m = ptnet("merge b.h5 a.h5 --out all.h5");
  ASSERT_EQ(m.status, 0) << m.err;
  EXPECT_EQ(m.out, "wrote all.h5\n");
  const auto whole = ptnet("info whole.h5 --json"), all = ptnet("info all.h5 --json");
  ASSERT_EQ(whole.status, 0);
  EXPECT_EQ(info_without_name(whole, "whole.h5"), info_without_name(all, "all.h5"));
  // Never over a user's file without --force.
  auto again = ptnet("merge a.h5 b.h5 --out all.h5");
  EXPECT_EQ(again.status, 1);
  EXPECT_EQ(again.err, "ptnet: error: all.h5: exists; pass --force to overwrite\n");
  EXPECT_EQ(ptnet("merge a.h5 b.h5 --out all.h5 --force").status, 0);
}

TEST_F(ShardCli, BadShardIsOneLineError) {
  // Whole decimal numbers that fit: 1/4294967298 is not 1/2 (2^32 + 2),
  // 0/4294967297 not 0/1 (unsharded).
  for (const std::string bad : {"2/2", "x", "1/0", "-1/2", "1/2x", "1/4294967298", "0/4294967297", "0x1/2", "1.0/2",
                                "+1/2"}) {
    auto r = ptnet(kSimulate + " --shard " + bad + " --out s.h5");
    EXPECT_EQ(r.status, 1) << bad;
    EXPECT_EQ(r.err.rfind("ptnet: error: --shard: expected K/N with 0 <= K < N", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  auto r = ptnet("merge missing.h5 --out m.h5");
  EXPECT_NE(r.status, 0);
  auto m = ptnet(kSimulate + " --shard 0/3 --out p0.h5");
  ASSERT_EQ(m.status, 0);
  r = ptnet("merge p0.h5 --out m.h5");
  EXPECT_EQ(r.err, "ptnet: error: merge: shard 1/3 is missing (1 of 3 given)\n");
  EXPECT_FALSE(fs::exists(dir_ / "m.h5"));
  EXPECT_FALSE(fs::exists(dir_ / "s.h5"));
}
