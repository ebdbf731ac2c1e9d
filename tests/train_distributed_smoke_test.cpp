// Distributed training on loopback through the real binary: two ranks with
// global batch B reach the weights of one process with batch B (the
// equivalence of docs/distributed.md), a rank killed with SIGKILL stops the
// other with a line naming it and the run resumes, and bad rendezvous
// options are one-line errors.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include "cli_test_util.hpp"
#include "ptnet/data.hpp"
#include "ptnet/model.hpp"
#include "ptnet/model_config.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
using ptnet::testing_cli::run_ptnet;
using ptnet::testing_cli::slurp;
using ptnet::testing_cli::wait_status;
namespace fs = std::filesystem;

namespace {

// A tiny frame network; 3 micro-batches per step (16, 16, 8 windows), so
// the ranks hold unequal shares: rank 0 micro-batches 0 and 2, rank 1 1.
const std::string kTrainArgs =
    " --preset fast --channels 4,8,8 --hidden 16 --epochs 1 --batch 40 --micro-batch 16"
    " --samples-per-epoch 160 --val-samples 48 --threads 1 --no-contact-threshold";

class Distributed : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ptnet_dist_smoke_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ptnet::testing::write_source(ptnet::testing::synth_source(4, 2, 90), (dir_ / "data.h5").string());
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static inline fs::path dir_;
  static std::string data() { return (dir_ / "data.h5").string(); }
  static fs::path scratch(const std::string& name) { return dir_ / name; }
};

// Parameters and buffers of a model folder's model.pt, by name.
std::vector<std::pair<std::string, torch::Tensor>> weights_of(const fs::path& model) {
  PressureTransferNet net(read_model_dir(model.string()).model);
  load_weights(net, (model / "model.pt").string());
  std::vector<std::pair<std::string, torch::Tensor>> out;
  for (const auto& p : net->named_parameters()) out.emplace_back(p.key(), p.value().clone());
  for (const auto& b : net->named_buffers()) out.emplace_back(b.key(), b.value().clone());
  return out;
}

// A ptnet process in the background, its stderr into `err`. Its ranks
// meet through a file:// rendezvous, on the loopback interface.
pid_t spawn(const std::string& args, const fs::path& err) {
  return ptnet::testing_cli::spawn_ptnet(args, err, "GLOO_SOCKET_IFNAME=lo");
}

}  // namespace

TEST_F(Distributed, TwoRanksReachTheWeightsOfOneProcess) {
  const fs::path one = dir_ / "one", two = dir_ / "two";
  auto r1 = run_ptnet("train --data " + data() + " --out " + one.string() + kTrainArgs, scratch("one"));
  ASSERT_EQ(r1.status, 0) << r1.err;
  auto r2 = run_ptnet("train --data " + data() + " --out " + two.string() + kTrainArgs + " --nproc 2", scratch("two"));
  ASSERT_EQ(r2.status, 0) << r2.err;
  EXPECT_NE(r2.err.find("2 ranks"), std::string::npos) << r2.err;
  EXPECT_EQ(r2.err.find("[epoch 1/1]"), r2.err.rfind("[epoch 1/1]")) << "progress from rank 0 only:\n" << r2.err;
  const auto a = weights_of(one), b = weights_of(two);
  ASSERT_EQ(a.size(), b.size());
  int compared = 0;
  double largest = 0;  // relative difference, printed for docs/distributed.md
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].first, b[i].first);
    const auto x = a[i].second.to(torch::kFloat64), y = b[i].second.to(torch::kFloat64);
    const double norm = x.norm().item<double>(), diff = (x - y).norm().item<double>();
    EXPECT_LE(diff, 1e-5 * std::max(norm, 1e-12)) << a[i].first << ": |a - b| " << diff << ", |a| " << norm;
    largest = std::max(largest, diff / std::max(norm, 1e-12));
    ++compared;
  }
  std::cout << "largest relative difference of " << compared << " tensors: " << largest << "\n";
  EXPECT_GT(compared, 0);
  // The step was taken: the weights moved from their seeded start.
  EXPECT_NE(read_model_dir(one.string()).integrity.value("model.pt", ""), "");
}

TEST_F(Distributed, KilledRankStopsTheOtherThenResume) {
  const fs::path model = dir_ / "killed";
  const std::string rdv = "file://" + (dir_ / "rendezvous-killed").string();
  const std::string args = "train --data " + data() + " --out " + model.string() +
                           " --preset fast --channels 4,8,8 --hidden 16 --epochs 1000 --batch 16 --micro-batch 8"
                           " --samples-per-epoch 64 --val-samples 16 --threads 1 --world-size 2 --rendezvous " + rdv;
  const pid_t r0 = spawn(args + " --rank 0", scratch("k0.err"));
  const pid_t r1 = spawn(args + " --rank 1", scratch("k1.err"));
  // Until an epoch is recorded (a checkpoint to resume from), at most 2 min.
  for (int i = 0; i < 1200 && !fs::exists(model / "history.csv"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_TRUE(fs::exists(model / "history.csv")) << slurp(scratch("k0.err"));
  ::kill(r1, SIGKILL);
  EXPECT_EQ(wait_status(r1), 128 + SIGKILL);
  EXPECT_EQ(wait_status(r0), 1);
  const std::string err = slurp(scratch("k0.err"));
  EXPECT_NE(err.find("ptnet: error: distributed: lost rank 1 during"), std::string::npos) << err;
  // Resume for one more epoch (one process: another world size takes the same steps).
  const std::string history = slurp(model / "history.csv");
  const int done = int(std::count(history.begin(), history.end(), '\n')) - 1;
  ASSERT_GE(done, 1) << history;
  auto r = run_ptnet("train --data " + data() + " --out " + model.string() +
                         " --preset fast --channels 4,8,8 --hidden 16 --epochs " + std::to_string(done + 1) +
                         " --batch 16 --micro-batch 8 --samples-per-epoch 64 --val-samples 16 --threads 1 --resume",
                     scratch("resume"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("resuming after epoch " + std::to_string(done)), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[epoch " + std::to_string(done + 1) + "/"), std::string::npos) << r.err;
  for (const auto& e : fs::directory_iterator(model))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(Distributed, BadRendezvousIsOneLineError) {
  const std::string base = "train --data " + data() + " --out " + (dir_ / "bad").string() + kTrainArgs;
  auto r = ptnet::testing_cli::run_program(
      PTNET_BINARY, base + " --world-size 2 --rank 1 --rendezvous tcp://127.0.0.1:1 --dist-timeout 1", scratch("b1"),
      {}, "PTNET_DIST_TOKEN=distributed-smoke-test-token");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("ptnet: error: --rendezvous tcp://127.0.0.1:1: rank 1 could not reach rank 0"),
            std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  // A port is decimal: 0x7000 is not 28672, 1e3 not 1000.
  for (const std::string bad : {"udp://x:1", "tcp://127.0.0.1:0x7000", "tcp://127.0.0.1:1e3", "tcp://127.0.0.1:65536"}) {
    r = run_ptnet(base + " --world-size 2 --rank 1 --dist-timeout 1 --rendezvous " + bad, scratch("b2"));
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("--rendezvous: expected tcp://HOST:PORT or file://PATH"), std::string::npos) << r.err;
  }
  r = run_ptnet(base + " --world-size 2 --rank 2 --rendezvous tcp://127.0.0.1:1", scratch("b3"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--rank: must be in 0-1, found 2"), std::string::npos) << r.err;
  r = run_ptnet(base + " --nproc 2 --rank 1", scratch("b4"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--nproc starts its own ranks"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

TEST_F(Distributed, WorldSizeMismatchIsOneLineError) {
  const std::string rdv = "file://" + (dir_ / "rendezvous-mismatch").string();
  const std::string base = "train --data " + data() + " --out " + (dir_ / "mismatch").string() + kTrainArgs +
                           " --dist-timeout 20 --rendezvous " + rdv;
  const pid_t r0 = spawn(base + " --world-size 2 --rank 0", scratch("m0.err"));
  const pid_t r1 = spawn(base + " --world-size 3 --rank 1", scratch("m1.err"));
  EXPECT_EQ(wait_status(r1), 1);
  EXPECT_EQ(wait_status(r0), 1);
  const std::string e0 = slurp(scratch("m0.err")), e1 = slurp(scratch("m1.err"));
  EXPECT_NE(e1.find("ptnet: error: --world-size: rank 1 was started with 3, rank 0 with 2"), std::string::npos) << e1;
  EXPECT_NE(e0.find("refused to join"), std::string::npos) << e0;
  EXPECT_FALSE(fs::exists(dir_ / "mismatch" / "model.pt"));
}
