// Training progress (issue 16): TrainOptions::progress is called after each
// optimiser step with (epoch, windows done, windows in the epoch); `ptnet
// train` shows a progress line inside each epoch on a terminal and keeps one
// plain line per epoch in a log.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "cli_test_util.hpp"
#include "data_test_util.hpp"
#include "ptnet/data.hpp"
#include "ptnet/train.hpp"
#include "support/memory_source.hpp"
#include "train_synthetic.hpp"

namespace ptnet {
namespace {

namespace fs = std::filesystem;
using testing_util::TempDir;

TEST(TrainProgress, CalledAfterEachOptimiserStep) {
  TempDir dir("train_progress");
  MemorySource src = testing::synth_source(4, 2, 90);
  TrainOptions o = testing::synth_options(/*epochs=*/2);
  o.samples_per_epoch = 100;  // batch 16: 6 full steps and one of 4
  std::vector<std::array<std::int64_t, 3>> calls;
  std::vector<std::string> lines;
  o.progress = [&](const Progress& p) {
    if (!p.line.empty()) lines.push_back(p.line);
    else calls.push_back({p.step, p.done, p.total});
  };
  train(src, dir.file("model"), o);
  ASSERT_EQ(calls.size(), 14u);
  for (std::size_t i = 0; i < calls.size(); ++i) {
    const std::int64_t step = std::int64_t(i % 7) + 1;
    EXPECT_EQ(calls[i][0], std::int64_t(i / 7) + 1);
    EXPECT_EQ(calls[i][1], std::min<std::int64_t>(16 * step, 100));
    EXPECT_EQ(calls[i][2], 100);
  }
  // The library prints nothing: its lines come through the same callback.
  ASSERT_EQ(lines.size(), 4u);  // setup, two epochs, final metrics
  EXPECT_EQ(lines[1].rfind("[epoch 1/2] train ", 0), 0u) << lines[1];
  EXPECT_EQ(lines[3].rfind("train: best epoch ", 0), 0u) << lines[3];
}

class TrainProgressCli : public ::testing::Test {
 protected:
  void SetUp() override {
    MemorySource src = testing::synth_source(4, 4, 150);  // ~1300 training windows
    DatasetInfo info;
    info.mat = src.mat();
    info.generator = "train_progress_test";
    DatasetWriter w(dir_.file("data.h5"), info, src.bodies(), false);
    for (const auto& m : src.sequences()) w.add(m, src.read_all(m.name));
    w.commit();
  }
  // `windows` per epoch in steps of 16: enough steps for a measured rate (> 0.2 s).
  std::string args(const std::string& out, int windows = 128) const {
    return "train --data '" + dir_.file("data.h5") + "' --out '" + dir_.file(out) +
           "' --preset fast --channels 8,16,32 --hidden 16 --latent 16 --epochs 2 --batch 16"
           " --samples-per-epoch " +
           std::to_string(windows) + " --val-samples 32 --threads 1";
  }
  TempDir dir_{"train_progress_cli"};
};

TEST_F(TrainProgressCli, ALogGetsOnePlainLinePerEpoch) {
  const auto r = testing_cli::run_ptnet(args("model"), dir_.path / "log");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("windows/s"), std::string::npos) << r.err;
  const std::regex epoch_line("\\[epoch [12]/2\\] train [0-9.]+ val [0-9.]+ lr ");
  EXPECT_EQ(std::distance(std::sregex_iterator(r.err.begin(), r.err.end(), epoch_line),
                          std::sregex_iterator()),
            2)
      << r.err;
}

TEST_F(TrainProgressCli, ATerminalGetsAProgressLineInsideEachEpoch) {
  if (std::system("command -v script >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "util-linux 'script' (a pty) is missing";
  // script(1) runs the tool on a pseudo-terminal and records what it shows.
  const std::string typescript = dir_.file("typescript");
  const std::string cmd = "script -qec \"'" + std::string(PTNET_BINARY) + "' " +
                          args("model_tty", 2048) + " >/dev/null\" '" + typescript +
                          "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string shown = testing_cli::slurp(typescript);
  EXPECT_TRUE(std::regex_search(shown, std::regex("epoch 1/2: 16/[0-9]+ windows"))) << shown;
  EXPECT_NE(shown.find("windows/s, ETA "), std::string::npos) << shown;
  EXPECT_NE(shown.find("run ETA "), std::string::npos) << shown;
  EXPECT_NE(shown.find("\r\033[K[epoch 1/2] train "), std::string::npos)
      << "the progress line is erased before the epoch line";
  EXPECT_NE(shown.find("[epoch 2/2] train "), std::string::npos) << shown;
}

}  // namespace
}  // namespace ptnet
