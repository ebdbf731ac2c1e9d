// The two executables (app/ptnet.cpp): `ptnet` runs the commands that need
// no LibTorch without loading it, and hands every other command line to
// `ptnet-torch` beside it (or, installed, in libexec/ptnet/); without
// ptnet-torch those say so in one line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;
using ptnet::testing_cli::RunResult;

namespace {

class FrontEnd : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ptnet_front_end_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "bodies.csv") << "id,sex,height_cm,weight_kg,role\nf1,female,160,58,retargeted\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `env exe args` in dir_.
  RunResult run(const fs::path& exe, const std::string& args, const std::string& env = "") const {
    return ptnet::testing_cli::run_program(exe, args, dir_ / ".run", dir_, env);
  }
  // The shared libraries the dynamic loader maps for `exe` (what ldd lists).
  std::string libraries(const fs::path& exe) const {
    const RunResult r = run(exe, "", "LD_TRACE_LOADED_OBJECTS=1");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("libc.so"), std::string::npos) << r.out;
    return r.out;
  }

  fs::path dir_;
};

}  // namespace

TEST_F(FrontEnd, PtnetLoadsNoLibTorchAndPtnetTorchDoes) {
  const fs::path ptnet = PTNET_BINARY, torch_exe = fs::path(PTNET_BINARY).parent_path() / "ptnet-torch";
  const std::string light = libraries(ptnet), full = libraries(torch_exe);
  EXPECT_EQ(light.find("libtorch"), std::string::npos) << light;
  EXPECT_EQ(light.find("libc10"), std::string::npos) << light;
  EXPECT_NE(full.find("libtorch"), std::string::npos) << full;  // the check can see LibTorch
}

TEST_F(FrontEnd, EveryCommandAnswersThroughPtnet) {
  const RunResult help = run(PTNET_BINARY, "--help");
  EXPECT_EQ(help.status, 0) << help.err;
  for (const char* command : {"simulate", "bodies", "info", "render", "train", "transfer", "evaluate", "stream"})
    EXPECT_NE(help.out.find(std::string("\n  ") + command + " "), std::string::npos) << command << "\n" << help.out;
  const RunResult train = run(PTNET_BINARY, "-q train --help");
  EXPECT_EQ(train.status, 0) << train.err;
  EXPECT_NE(train.out.find("--preset"), std::string::npos) << train.out;
  const RunResult version = run(PTNET_BINARY, "--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.out.rfind("ptnet ", 0), 0u) << version.out;
  // A model command's usage error comes from ptnet-torch, as one line, status 2.
  const RunResult usage = run(PTNET_BINARY, "train --epochs 0");
  EXPECT_EQ(usage.status, 2) << usage.err;
  EXPECT_EQ(std::count(usage.err.begin(), usage.err.end(), '\n'), 1) << usage.err;
}

TEST_F(FrontEnd, WithoutPtnetTorchTheModelCommandsSaySoAndTheOthersRun) {
  const fs::path alone = dir_ / "bin" / "ptnet";
  fs::create_directories(alone.parent_path());
  fs::copy_file(PTNET_BINARY, alone);
  const RunResult bodies = run(alone, "-q bodies --seed 1 --out b.csv");
  EXPECT_EQ(bodies.status, 0) << bodies.err;
  EXPECT_TRUE(fs::exists(dir_ / "b.csv"));
  const RunResult train = run(alone, "train --data d.h5 --out m");
  EXPECT_EQ(train.status, 1) << train.err;
  EXPECT_EQ(train.err, "ptnet: error: ptnet-torch: found neither " + (dir_ / "bin" / "ptnet-torch").string() +
                           " nor " + (dir_ / "libexec" / "ptnet" / "ptnet-torch").string() +
                           "; the model commands live there: build it (make build) or reinstall ptnet\n");
  EXPECT_FALSE(fs::exists(dir_ / "m"));
}

// OpenMP threads that wait for each other sleep instead of spinning, unless
// the user chose (docs/model.md, "Threads"): a stand-in ptnet-torch beside
// ptnet prints what it was given.
TEST_F(FrontEnd, PtnetTorchWaitsPassivelyUnlessTheUserChose) {
  const fs::path ptnet = dir_ / "bin" / "ptnet";
  fs::create_directories(ptnet.parent_path());
  fs::copy_file(PTNET_BINARY, ptnet);
  std::ofstream(dir_ / "bin" / "ptnet-torch") << "#!/bin/sh\necho \"${OMP_WAIT_POLICY:-unset}\"\n";
  fs::permissions(dir_ / "bin" / "ptnet-torch", fs::perms::owner_all);
  const std::string clean = "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT";
  EXPECT_EQ(run(ptnet, "train", clean).out, "PASSIVE\n");
  EXPECT_EQ(run(ptnet, "train", clean + " OMP_WAIT_POLICY=ACTIVE").out, "ACTIVE\n");
  EXPECT_EQ(run(ptnet, "train", clean + " GOMP_SPINCOUNT=10000").out, "unset\n");
  EXPECT_EQ(run(ptnet, "bodies --seed 1 --out b.csv", clean).out.find("PASSIVE"), std::string::npos);
}

// Installed (cmake/install.cmake), ptnet is PREFIX/bin/ptnet and ptnet-torch
// PREFIX/libexec/ptnet/ptnet-torch.
TEST_F(FrontEnd, InstalledPtnetFindsPtnetTorchInLibexec) {
  const fs::path ptnet = dir_ / "prefix" / "bin" / "ptnet", torch_exe = dir_ / "prefix" / "libexec" / "ptnet" / "ptnet-torch";
  fs::create_directories(ptnet.parent_path());
  fs::create_directories(torch_exe.parent_path());
  fs::copy_file(PTNET_BINARY, ptnet);
  fs::create_symlink(fs::path(PTNET_BINARY).parent_path() / "ptnet-torch", torch_exe);
  const RunResult usage = run(ptnet, "train --epochs 0");
  EXPECT_EQ(usage.status, 2) << usage.err;  // ptnet-torch's CLI11 answered
  EXPECT_NE(usage.err.find("--epochs"), std::string::npos) << usage.err;
}
