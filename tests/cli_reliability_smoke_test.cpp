// The real tool as a careless or hostile user drives it: usage errors are one
// line with the prefix and status 2, every numeric option is range-checked
// (NaN too) with short numbers, no output replaces an input (same inode) or
// a non-regular file (a FIFO stands in for a device node), and NaN in a .npy
// input is rejected as in a dataset.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli_test_util.hpp"
#include "data_test_util.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/train.hpp"
#include "support/memory_source.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
using ptnet::testing_cli::RunResult;
using ptnet::testing_cli::slurp;
namespace fs = std::filesystem;

namespace {

class Reliability : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ptnet_cli_reliability_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "bodies.csv") << "id,sex,height_cm,weight_kg,role\nb1,female,160,55,retargeted\n";
    // A tiny model on a 16 x 8 mat for the transfer cases.
    const MemorySource src = ptnet::testing::synth_source(3, 2, 90);
    train(src, (dir_ / "model").string(), ptnet::testing::synth_options(1));
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static RunResult run(const std::string& args) {
    return ptnet::testing_cli::run_ptnet(args, dir_ / "scratch", dir_);
  }
  // Status 2 and one line "ptnet: error: ..." holding `what`, with no long number.
  static void expect_usage_error(const std::string& args, const std::string& what) {
    const RunResult r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ptnet: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << args << "\n" << r.err;
    EXPECT_LT(r.err.size(), 300u) << r.err;  // no 309-digit DBL_MAX
  }
  static inline fs::path dir_;
};

}  // namespace

TEST_F(Reliability, UsageErrorsAreOneLineWithStatus2) {
  expect_usage_error("no-such-command", "'no-such-command': not a command");
  expect_usage_error("train --data d.h5 --out m --epochs 0", "--epochs");
  expect_usage_error("train --data d.h5 --out m --threads 100000", "--threads");
  expect_usage_error("train --data d.h5 --out m --threads -1", "--threads");
  expect_usage_error("train --data d.h5 --out m --samples-per-epoch -5", "--samples-per-epoch");
  expect_usage_error("train --data d.h5 --out m --val-samples -5", "--val-samples");
  expect_usage_error("train --data d.h5 --out m --cache-mb -5", "--cache-mb");
  expect_usage_error("train --data d.h5 --out m --lr nan", "--lr: 'nan' is not in (0, 10]");
  expect_usage_error("transfer --model m --in a.npy --target male,180,80 --out b.npy --threads 100000", "--threads");
  expect_usage_error("evaluate --model m --data d.h5 --threads 100000", "--threads");
  expect_usage_error("simulate --embedded --bodies bodies.csv --out x.h5 --noise-kpa nan", "--noise-kpa");
  expect_usage_error("simulate --embedded --bodies bodies.csv --out x.h5 --saturation-kpa -1",
                     "--saturation-kpa: '-1' is not in (0, 1000000]");
  expect_usage_error("render d.h5 -s a --out a.png --vmax nan", "--vmax");
  expect_usage_error("train --data", "--data");
}

// A list option with an item twice (after its normalisation: lower case,
// a speed's label) is one line and exit 1 before any work; before, har-bench
// scored xsmall twice, simulate simulated every sequence before "added
// twice", render drew a sequence or frame twice.
TEST_F(Reliability, ListsWithAnItemTwiceAreRefusedBeforeAnyWork) {
  const std::string sim = "-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies bodies.csv ";
  ASSERT_EQ(run(sim + "--out lists.h5").status, 0);
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"har-bench --deployment-bands xsmall,xlarge,xsmall --out hb",
            "har-bench: deployment band 'xsmall' given twice"},
           {"har-bench --syntheses copy,body-scale,COPY --out hb", "har-bench: training source 'copy' given twice"},
           {sim + "--speeds 0.8,0.8000001 --out speeds.h5",
            "--speeds: 0.8000001 has more digits than its label _x0.8 shows (at most 6 significant digits)"},
           {sim + "--speeds 1.000001 --out speeds.h5",
            "--speeds: 1.000001 has more digits than its label _x1 shows (at most 6 significant digits)"},
           {"render lists.h5 -s p1_walking_t1__b1 -s p1_walking_t1__b1 --out twice.png",
            "render: --sequence: 'p1_walking_t1__b1' given twice"},
           {"render lists.h5 -s p1_walking_t1__b1 --frame-list 0,5,0 --out twice.png",
            "--frame-list: frame 0 given twice"}}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err, "ptnet: error: " + message + "\n") << args;
  }
  for (const char* out : {"hb", "speeds.h5", "twice.png"}) EXPECT_FALSE(fs::exists(dir_ / out)) << out;
}

// Readings no mat makes (tests/data/pressure_range): before, 3e38 kPa was
// transferred into all zeros and -0.5 kPa passed, both with exit 0.
TEST_F(Reliability, PressureOutsideThePhysicalRangeIsRefused) {
  for (const auto& [file, value] : {std::pair{"pressure_3e38.npy", "3e+38"}, std::pair{"pressure_negative.npy", "-0.5"}}) {
    const std::string in = std::string(PTNET_TEST_DATA) + "/pressure_range/" + file;
    const RunResult r = run("-q transfer --model model --in " + in + " --source female,165,60 --target male,185,90 "
                            "--out absurd.npy");
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(r.err, "ptnet: error: " + in + ": " + value + " kPa in frame 2, outside [0, 1000000] kPa\n");
    EXPECT_FALSE(fs::exists(dir_ / "absurd.npy"));
  }
}

// Counts beyond their range are one line naming the range (before,
// --originals 2,1000000000 ended in "out of memory").
TEST_F(Reliability, BodyCountsHaveTheirRange) {
  const RunResult r = run("bodies --originals 2,1000000000 --out counts.csv");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err, "ptnet: error: --originals: expected FEMALES,MALES like 2,2, each in [0, 10000], found "
                   "'2,1000000000'\n");
  expect_usage_error("bodies --males 10001 --out counts.csv", "--males");
  EXPECT_FALSE(fs::exists(dir_ / "counts.csv"));
}

TEST_F(Reliability, SimulateNeverReplacesItsBodiesCsv) {
  const std::string before = slurp(dir_ / "bodies.csv");
  // A .csv name is no dataset's: refused by its format first.
  const RunResult r = run("-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies bodies.csv "
                          "--out bodies.csv --force");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("bodies.csv: expected a .h5 or .hdf5 file name"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "bodies.csv"), before);
  // The same file through a dataset's name (a hard link): refused as the input.
  fs::create_hard_link(dir_ / "bodies.csv", dir_ / "alias.h5");
  const RunResult a = run("-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies bodies.csv "
                          "--out alias.h5 --force");
  EXPECT_EQ(a.status, 1);
  EXPECT_NE(a.err.find("same file as the input"), std::string::npos) << a.err;
  EXPECT_EQ(slurp(dir_ / "bodies.csv"), before);
}

TEST_F(Reliability, AFifoOutputIsRefusedEvenWithForce) {
  for (const std::string name : {"device.h5", "device.csv"}) {
    const fs::path fifo = dir_ / name;
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  }
  const RunResult r = run("-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies bodies.csv "
                          "--out device.h5 --force");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: device.h5: is a FIFO, not a regular file; refusing to replace it (even with --force)\n");
  struct stat st;
  ASSERT_EQ(::stat((dir_ / "device.h5").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  const RunResult b = run("bodies --out device.csv --force");
  EXPECT_EQ(b.status, 1);
  EXPECT_NE(b.err.find("is a FIFO"), std::string::npos) << b.err;
}

TEST_F(Reliability, TransferNeverReplacesItsInput) {
  const MatSpec mat{ptnet::testing::kSynthRows, ptnet::testing::kSynthCols, 0.02};
  PressureSequence s(mat, 40, 30);
  for (std::size_t i = 0; i < s.kpa.size(); ++i) s.kpa[i] = float(i % 7);
  write_npy_sequence((dir_ / "in.npy").string(), s, true);
  const std::string before = slurp(dir_ / "in.npy");
  const RunResult r =
      run("-q transfer --model model --in in.npy --source female,165,60 --target male,185,90 --out in.npy --force");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("in.npy: is the same file as the input in.npy"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "in.npy"), before);
  // A good run writes elsewhere.
  const RunResult ok =
      run("-q transfer --model model --in in.npy --source female,165,60 --target male,185,90 --out out.npy");
  EXPECT_EQ(ok.status, 0) << ok.err;
  // NaN in a .npy is rejected as in a dataset.
  s.at(3, 2, 1) = std::nanf("");
  write_npy_sequence((dir_ / "nan.npy").string(), s, true);
  const RunResult n =
      run("-q transfer --model model --in nan.npy --source female,165,60 --target male,185,90 --out nan_out.npy");
  EXPECT_EQ(n.status, 1);
  EXPECT_EQ(n.err, "ptnet: error: nan.npy: non-finite value (NaN or Inf) in frame 3\n");
  EXPECT_FALSE(fs::exists(dir_ / "nan_out.npy"));
}

TEST_F(Reliability, ImportNeverReplacesItsDataset) {
  ptnet::testing_util::write_small_dataset((dir_ / "real.h5").string(), 70, 5, /*force=*/true);
  const std::string before = slurp(dir_ / "real.h5");
  const RunResult r = run("-q import --dataset real.h5 --subjects b1 --out real.h5 --force");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("real.h5: is the same file as the input real.h5"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "real.h5"), before);
}
