// `ptnet simulate` end to end (the real binary): a small --embedded run
// writes a dataset that `ptnet info` reads; the same seed gives a
// byte-identical file (whatever the thread count), another seed a different
// one; every bad input exits 1 with one line "ptnet: error: <file>: <problem>"
// and leaves no output (nor temporary) file behind.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;

namespace {

using ptnet::testing_cli::RunResult;
using ptnet::testing_cli::slurp;

void spit(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

class SimulateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ptnet_simulate_smoke_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    spit(dir_ / "bodies.csv", "id,sex,height_cm,weight_kg,role\nf1,female,160,58,retargeted\nm1,male,185,86,original\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs ptnet in dir_ with `args`.
  RunResult run(const std::string& args) const { return ptnet::testing_cli::run_ptnet(args, dir_ / ".run", dir_); }

  // Outputs or temporaries in dir_ (.h5 files, dot files) other than `inputs`.
  int stray_files(const std::vector<std::string>& inputs) const {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      const bool output = e.path().extension() == ".h5" || name[0] == '.';
      if (output && std::find(inputs.begin(), inputs.end(), name) == inputs.end())
        ++n, ADD_FAILURE() << "left behind: " << name;
    }
    return n;
  }

  // Expects exit 1, one stderr line "ptnet: error: " holding every `parts`, no output.
  void expect_error(const std::string& args, const std::vector<std::string>& parts,
                    const std::vector<std::string>& inputs) const {
    const RunResult r = run("-q simulate " + args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ptnet: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line: " << r.err;
    for (const auto& p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << "'" << p << "' not in: " << r.err;
    EXPECT_EQ(stray_files(inputs), 0) << args;
  }

  fs::path dir_;
};

const char* kSmall = "--embedded --performers 1 --takes 1 --seconds 2 --bodies bodies.csv";

TEST_F(SimulateCli, EmbeddedRunIsReadableAndDeterministic) {
  RunResult r = run(std::string("simulate ") + kSmall + " --seed 5 --threads 2 --out a.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("wrote a.h5"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("simulate: 8 sequences"), std::string::npos) << r.err;  // progress on stderr
  r = run("info a.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("sequences  8 (4 motions)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("acting 2, freestyle 2, rom 2, walking 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ptnet 0.1.0 simulate"), std::string::npos) << r.out;

  // Same seed (one thread this time): the same bytes. Another seed: different.
  ASSERT_EQ(run(std::string("-q simulate ") + kSmall + " --seed 5 --threads 1 --out b.h5").status, 0);
  ASSERT_EQ(run(std::string("-q simulate ") + kSmall + " --seed 6 --out c.h5").status, 0);
  EXPECT_EQ(run("-q simulate --help").status, 0);
  EXPECT_EQ(slurp(dir_ / "a.h5"), slurp(dir_ / "b.h5"));
  EXPECT_EQ(std::system(("cmp -s '" + (dir_ / "a.h5").string() + "' '" + (dir_ / "b.h5").string() + "'").c_str()), 0);
  EXPECT_NE(slurp(dir_ / "a.h5"), slurp(dir_ / "c.h5"));

  // Never overwrites without --force; with it, replaces the file.
  const auto before = fs::last_write_time(dir_ / "a.h5");
  r = run(std::string("-q simulate ") + kSmall + " --seed 5 --out a.h5");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: a.h5: exists; pass --force to overwrite\n");
  EXPECT_EQ(fs::last_write_time(dir_ / "a.h5"), before);
  EXPECT_EQ(run(std::string("-q simulate ") + kSmall + " --seed 6 --out a.h5 --force").status, 0);
  EXPECT_EQ(slurp(dir_ / "a.h5"), slurp(dir_ / "c.h5"));
}

TEST_F(SimulateCli, RealClipsWithClipsCsv) {
  const fs::path mocap = PTNET_SHARED_MOCAP;
  if (!fs::exists(mocap / "clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  fs::copy_file(mocap / "002_01.bvh", dir_ / "walk.bvh");
  spit(dir_ / "clips.csv", "file,subject,trial,category,take,metres_per_unit,up\nwalk.bvh,2,1,walking,2,0.01,y\n");
  RunResult r = run("-q simulate --motions walk.bvh --clips clips.csv --bodies bodies.csv --out m.h5");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("info m.h5 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* s : {"\"walk__f1\"", "\"walk__m1\"", "\"walking\"", "\"performer\": \"2\"", "\"take\": 2"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << " not in " << r.out.substr(0, 2000);
}

// Every clip of the CMU corpus (60 fps files with Frame Time 0.016667,
// 120 fps ones with .0083333) at every common rate: before the fix --fps
// 60 and 120 failed after simulating every sequence ("fps 59.9988 differs
// from the dataset's 60").
TEST_F(SimulateCli, EveryCommonFpsOnTheWholeCorpus) {
  const fs::path corpus = PTNET_SHARED_CORPUS;
  if (!fs::exists(corpus / "clips.csv")) GTEST_SKIP() << "../shared/mocap-corpus not found";
  for (const int fps : {25, 30, 50, 60, 100, 120}) {
    const std::string out = "corpus" + std::to_string(fps) + ".h5";
    RunResult r = run("-q simulate --clips '" + (corpus / "clips.csv").string() +
                      "' --bodies bodies.csv --no-floor --threads 2 --fps " + std::to_string(fps) + " --out " + out);
    ASSERT_EQ(r.status, 0) << fps << " fps: " << r.err;
    r = run("info " + out + " --json");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("\"fps\": " + std::to_string(fps)), std::string::npos) << r.out.substr(0, 400);
    fs::remove(dir_ / out);
  }
}

// A marker trial at 100 Hz (the real treadmill walk, its 151 frames
// relabelled 100 Hz: DataRate and the Time column) at every common rate.
TEST_F(SimulateCli, EveryCommonFpsOnAMarkerTrialAt100Hz) {
  const fs::path trial = fs::path(PTNET_SHARED_GAIT) / "walk_s01.trc";
  if (!fs::exists(trial)) GTEST_SKIP() << "../shared/real-gait not found";
  std::istringstream in(slurp(trial));
  std::string text, line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (n == 3) {
      line = "100.00\t100.00\t151\t41\tmm\t100.00\t1\t151";
    } else if (n >= 6 && !line.empty()) {
      const auto a = line.find('\t'), b = line.find('\t', a + 1);
      const int frame = std::stoi(line.substr(0, a));
      char time[32];
      std::snprintf(time, sizeof time, "%.6f", (frame - 1) / 100.0);
      line = line.substr(0, a + 1) + time + line.substr(b);
    }
    text += line + "\n";
  }
  spit(dir_ / "walk100.trc", text);
  for (const int fps : {25, 30, 50, 60, 100, 120}) {
    const std::string out = "walk100_" + std::to_string(fps) + ".h5";
    RunResult r = run("-q simulate --motions walk100.trc --bodies bodies.csv --no-floor --threads 2 --fps " +
                      std::to_string(fps) + " --out " + out);
    ASSERT_EQ(r.status, 0) << fps << " fps: " << r.err;
    r = run("info " + out + " --json");
    EXPECT_NE(r.out.find("\"fps\": " + std::to_string(fps)), std::string::npos) << r.out.substr(0, 400);
    // 151 frames at 100 Hz: 1.5 s, so 1.5 F frames + 1 (after a leading T-pose? none in a marker file).
    EXPECT_NE(r.out.find("\"frames\": " + std::to_string(int(1.5 * fps) + 1)), std::string::npos)
        << fps << " fps: " << r.out.substr(0, 2000);
  }
}

TEST_F(SimulateCli, BadInputIsOneLineExitOneAndNoFile) {
  const std::vector<std::string> base{"bodies.csv"};
  expect_error("--motions missing.bvh --bodies bodies.csv --out o.h5", {"missing.bvh", "no such file"}, base);

  spit(dir_ / "bad.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n");
  expect_error("--motions bad.bvh --bodies bodies.csv --out o.h5", {"bad.bvh:5", "expected"}, {"bodies.csv", "bad.bvh"});

  spit(dir_ / "hdr.csv", "name,sex,h,w\nb,male,170,70\n");
  expect_error(std::string(kSmall).replace(std::string(kSmall).find("bodies.csv"), 10, "hdr.csv") + " --out o.h5",
               {"hdr.csv:1", "expected a header with column id (id,sex,height_cm,weight_kg[,role])"}, {"bodies.csv", "hdr.csv"});

  spit(dir_ / "range.csv", "id,sex,height_cm,weight_kg\nb1,male,300,70\n");
  expect_error("--embedded --bodies range.csv --out o.h5", {"range.csv:2", "height_cm", "300"},
               {"bodies.csv", "range.csv"});

  spit(dir_ / "clips.csv", "file,subject,category,take\nnope.bvh,1,walking,1\n");
  expect_error("--clips clips.csv --bodies bodies.csv --out o.h5", {"clips.csv:2", "clip file 'nope.bvh': no such file"},
               {"bodies.csv", "clips.csv"});

  spit(dir_ / "a.bvh", "x");
  spit(dir_ / "listed.csv", "file,subject,category,take\nb.bvh,1,walking,1\n");
  spit(dir_ / "b.bvh", "x");
  expect_error("--motions a.bvh --clips listed.csv --bodies bodies.csv --out o.h5", {"a.bvh", "not listed in listed.csv"},
               {"bodies.csv", "a.bvh", "b.bvh", "listed.csv"});

  expect_error(std::string(kSmall) + " --out /nonexistent_dir/x.h5", {"/nonexistent_dir/x.h5", "does not exist"}, base);
  // A folder where no file can be created, even by root.
  expect_error(std::string(kSmall) + " --out /proc/ptnet_x.h5", {"/proc/ptnet_x.h5", "cannot write"}, base);
  if (::geteuid() != 0) {
    fs::create_directories(dir_ / "ro");
    fs::permissions(dir_ / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    expect_error(std::string(kSmall) + " --out ro/x.h5", {"ro/x.h5", "not writable"}, {"bodies.csv", "ro"});
    fs::permissions(dir_ / "ro", fs::perms::owner_all);
  }

  spit(dir_ / "exists.h5", "keep");
  expect_error(std::string(kSmall) + " --out exists.h5", {"exists.h5", "exists; pass --force"}, {"bodies.csv", "exists.h5"});
  EXPECT_EQ(slurp(dir_ / "exists.h5"), "keep");
}

}  // namespace
