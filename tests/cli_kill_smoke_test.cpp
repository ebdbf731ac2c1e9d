// Interrupted runs: simulate, train and evaluate are killed at random points
// (kill -9 and SIGTERM, 20 times each) on a small dataset. Whatever is at the
// output path afterwards is complete (a dataset that opens and reads, model
// files whose archives verify, report files that parse), and a SIGTERM leaves
// no temporary file of the killed process; a later complete run sweeps those
// that kill -9 left.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "core/zip_check.hpp"
#include "ptnet/data.hpp"
#include "ptnet/model_config.hpp"

using namespace ptnet;
namespace fs = std::filesystem;

namespace {

constexpr int kKillsPerSignal = 20;

// Runs ptnet ARGS in `dir`; with `kill_after_s` >= 0 sends `sig` then. Returns
// the pid (for its temporary files) and whether it exited 0.
struct Outcome {
  pid_t pid = 0;
  bool ok = false;
  double seconds = 0;
};

Outcome run_ptnet(const fs::path& dir, const std::vector<std::string>& args, double kill_after_s = -1,
                  int sig = SIGTERM) {
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(126);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    std::vector<char*> argv{const_cast<char*>(PTNET_BINARY)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(PTNET_BINARY, argv.data());
    ::_exit(127);
  }
  int status = 0;
  if (kill_after_s >= 0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(kill_after_s));
    ::kill(pid, sig);
  }
  ::waitpid(pid, &status, 0);
  Outcome o;
  o.pid = pid;
  o.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return o;
}

// Temporary files under `dir`: all, or those of process `pid`.
std::vector<std::string> temps(const fs::path& dir, pid_t pid = 0) {
  std::vector<std::string> out;
  const std::string suffix = ".tmp" + std::to_string(pid);
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    const auto at = name.rfind(".tmp");
    if (name.empty() || name[0] != '.' || at == std::string::npos) continue;
    if (pid == 0 ? name.find_first_not_of("0123456789", at + 4) == std::string::npos
                 : name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(e.path().string());
  }
  return out;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Every file at the output is complete (throws or fails otherwise).
void expect_complete_dataset(const fs::path& p) {
  if (!fs::exists(p)) return;
  const Dataset d = Dataset::open(p.string());
  EXPECT_GT(d.sequences().size(), 0u);
  for (const auto& m : d.sequences()) EXPECT_EQ(d.read(m.name).frames(), m.frames);
}

void expect_complete_model(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  if (fs::exists(dir / "config.json")) EXPECT_NO_THROW(read_model_dir(dir.string())) << dir;
  for (const char* f : {"model.pt", "checkpoint.pt"})
    if (fs::exists(dir / f)) EXPECT_NO_THROW(verify_zip_file((dir / f).string())) << f;
  if (fs::exists(dir / "history.csv")) EXPECT_EQ(slurp(dir / "history.csv").rfind("epoch,", 0), 0u);
}

void expect_complete_report(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  if (fs::exists(dir / "metrics.json"))
    EXPECT_TRUE(nlohmann::json::accept(slurp(dir / "metrics.json"))) << "metrics.json is no complete JSON";
  if (fs::exists(dir / "metrics.csv")) EXPECT_TRUE(ends_with(slurp(dir / "metrics.csv"), "\n"));
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string bytes = slurp(e.path());
    if (e.path().extension() == ".png") EXPECT_NE(bytes.find("IEND", bytes.size() - 12), std::string::npos) << e.path();
    if (e.path().extension() == ".gif") EXPECT_TRUE(!bytes.empty() && bytes.back() == ';') << e.path();
  }
}

class Kill : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ptnet_cli_kill_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "bodies.csv") << "id,sex,height_cm,weight_kg,role\n"
                                          "r1,female,160,55,retargeted\nr2,male,182,84,retargeted\n"
                                          "o1,female,168,62,original\no2,male,176,75,original\n";
    base_ = run_ptnet(dir_, simulate_args("data.h5"));
    ASSERT_TRUE(base_.ok) << "simulate failed";
    train_ = run_ptnet(dir_, train_args("model"));
    ASSERT_TRUE(train_.ok) << "train failed";
    eval_ = run_ptnet(dir_, evaluate_args("report"));
    ASSERT_TRUE(eval_.ok) << "evaluate failed";
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::vector<std::string> simulate_args(const std::string& out) {
    return {"-q", "simulate", "--embedded", "--performers", "1", "--takes", "2", "--seconds", "3",
            "--threads", "2", "--bodies", "bodies.csv", "--out", out, "--force"};
  }
  static std::vector<std::string> train_args(const std::string& out) {
    return {"-q", "train", "--data", "data.h5", "--out", out, "--preset", "fast", "--epochs", "2",
            "--samples-per-epoch", "64", "--val-samples", "32", "--channels", "4,8,8", "--hidden", "16",
            "--latent", "16", "--force"};
  }
  static std::vector<std::string> evaluate_args(const std::string& out) {
    return {"-q", "evaluate", "--model", "model", "--data", "data.h5", "--out", out, "--stride", "15", "--force"};
  }

  // 20 x kill -9 and 20 x SIGTERM at uniform random times within a full run.
  template <class Check>
  void kill_repeatedly(const std::vector<std::string>& args, double full_run_s, const fs::path& out, Check check) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> when(0.0, full_run_s);
    for (int i = 0; i < 2 * kKillsPerSignal; ++i) {
      const int sig = i % 2 ? SIGTERM : SIGKILL;
      const Outcome o = run_ptnet(dir_, args, when(rng), sig);
      check(out);
      if (sig == SIGTERM) EXPECT_EQ(temps(dir_, o.pid), std::vector<std::string>{}) << "run " << i;
    }
    // A complete run sweeps what kill -9 left of its outputs.
    ASSERT_TRUE(run_ptnet(dir_, args).ok);
    check(out);
    EXPECT_EQ(temps(out.has_extension() ? dir_ : out), std::vector<std::string>{});
  }

  static inline fs::path dir_;
  static inline Outcome base_, train_, eval_;
};

}  // namespace

TEST_F(Kill, SimulateNeverLeavesAPartialDataset) {
  kill_repeatedly(simulate_args("sim.h5"), base_.seconds, dir_ / "sim.h5", expect_complete_dataset);
}

TEST_F(Kill, TrainNeverLeavesAPartialModelFile) {
  kill_repeatedly(train_args("m"), train_.seconds, dir_ / "m", expect_complete_model);
}

TEST_F(Kill, EvaluateNeverLeavesAPartialReportFile) {
  kill_repeatedly(evaluate_args("r"), eval_.seconds, dir_ / "r", expect_complete_report);
}
