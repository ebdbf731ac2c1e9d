// End to end through the real binary: `ptnet train` on a small synthetic
// dataset file, then `ptnet transfer` to .npy and .h5, and the CLI's errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli_test_util.hpp"
#include "core/npy_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/transfer.hpp"
#include "support/memory_source.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
namespace fs = std::filesystem;

namespace {

struct CmdResult {
  int status;
  std::string err;
};

CmdResult run(const std::string& args) {
  const fs::path err = fs::temp_directory_path() / ("ptnet_train_cli_smoke_" + std::to_string(::getpid()) + ".err");
  const std::string cmd = std::string(PTNET_BINARY) + " " + args + " 2> " + err.string() + " > /dev/null";
  int status = std::system(cmd.c_str());
  std::ifstream f(err);
  return {WEXITSTATUS(status), std::string(std::istreambuf_iterator<char>(f), {})};
}

class CliSmoke : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ptnet_train_cli_smoke_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    ptnet::testing::write_source(ptnet::testing::synth_source(4, 2, 90), (dir_ / "data.h5").string());
  }
  static inline fs::path dir_;
  std::string data() const { return (dir_ / "data.h5").string(); }
};

}  // namespace

TEST_F(CliSmoke, TrainThenTransferToNpyAndH5) {
  const std::string model = (dir_ / "model").string();
  CmdResult t = run("train --data " + data() + " --out " + model +
              " --preset fast --channels 4,8,8 --hidden 16 --latent 16 --epochs 2 --batch 16"
              " --samples-per-epoch 64 --val-samples 32 --threads 1");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_NE(t.err.find("[epoch 1/2] train "), std::string::npos) << t.err;
  EXPECT_NE(t.err.find("[epoch 2/2] train "), std::string::npos) << t.err;
  EXPECT_TRUE(fs::exists(fs::path(model) / "model.pt"));

  // Transfer a dataset sequence (source body read from the file) to .npy.
  const std::string out_npy = (dir_ / "out.npy").string();
  CmdResult r = run("transfer --model " + model + " --in " + data() + " --sequence m2__orig --target male,185,95 --out " + out_npy);
  ASSERT_EQ(r.status, 0) << r.err;
  NpyArray a = read_npy(out_npy);
  EXPECT_EQ(a.shape, (std::vector<std::int64_t>{90, 16, 8}));
  // The same through the API gives the same numbers.
  Dataset d = Dataset::open(data());
  Transfer api(model);
  PressureSequence expect = api.run(d.read("m2__orig"), d.body("orig"), BodySpec{"t", Sex::male, 185, 95});
  EXPECT_EQ(a.data, expect.kpa);

  // The sex word in any case, as the library's parser takes it.
  const std::string out_case = (dir_ / "out_case.npy").string();
  r = run("transfer --model " + model + " --in " + data() + " --sequence m2__orig --target Male,185,95 --out " + out_case);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_npy(out_case).data, expect.kpa);

  // .npy in, .h5 out: a one-sequence dataset on the target body.
  const std::string out_h5 = (dir_ / "out.h5").string();
  r = run("transfer --model " + model + " --in " + out_npy + " --source male,185,95 --target female,160,55 --out " + out_h5);
  ASSERT_EQ(r.status, 0) << r.err;
  Dataset o = Dataset::open(out_h5);
  ASSERT_EQ(o.sequences().size(), 1u);
  EXPECT_EQ(o.sequences()[0].frames, 90);
  EXPECT_EQ(o.bodies()[0].height_cm, 160);

  // Errors: one line, exit 1.
  r = run("transfer --model " + model + " --in " + out_npy + " --source male,185,95 --target female,160,55 --out " + out_h5);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + out_h5 + ": exists; pass --force to overwrite\n");
  r = run("transfer --model " + model + " --in " + out_npy + " --target female,160,55 --out " + (dir_ / "x.npy").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: --source is required with a .npy input (e.g. --source female,165,60)\n");
  r = run("transfer --model " + model + " --in " + out_npy + " --source male,185,95 --target giant,300 --out " +
          (dir_ / "x.npy").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: --target: expected SEX,HEIGHT_CM,WEIGHT_KG like female,165,60, found 'giant,300'\n");
  r = run("transfer --model " + model + " --in " + out_npy + " --source male,185,95 --target male,300,80 --out " +
          (dir_ / "x.npy").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: target body: height_cm 300 outside 100-230\n");
  r = run("train --data " + data() + " --out " + model + " --preset fast --epochs 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + model + ": exists; pass --force to overwrite or --resume to continue\n");
  r = run("train --data " + data() + " --out " + model + " --preset quick");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: --preset: expected paper, fast or full, found \"quick\"\n");
  r = run("train --data " + data());
  EXPECT_EQ(r.status, 2);  // usage error: --out missing
  fs::remove_all(dir_);
}

// A model no better than doing nothing (a learning rate that leaves the
// initial weights) is kept and reported: by `train` in a warning line naming
// the all-zero and the copy baseline's validation RMSE (an error with
// --strict), by `evaluate` in the same words, atop its page and in its
// metrics.json (scripts/lopo.sh prints it), by `transfer` too. Before, all
// said nothing.
TEST(CliBaselines, AModelNoBetterThanTheBaselinesIsReported) {
  const fs::path dir = fs::temp_directory_path() / ("ptnet_train_baselines_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A second original body, for evaluate's test pairs.
  MemorySource src = ptnet::testing::synth_source(4, 2, 90);
  const BodySpec second{"orig2", Sex::male, 181, 77, "original"};
  src.add_body(second);
  for (const SequenceMeta& m : std::vector<SequenceMeta>(src.sequences()))
    if (m.body_id == "orig") {
      SequenceMeta o = m;
      o.body_id = second.id;
      o.name = m.motion_id + "__" + second.id;
      src.add_sequence(o, ptnet::testing::synth_sequence(std::stoi(m.motion_id.substr(1)), second, 90, src.mat()));
    }
  const std::string data = (dir / "data.h5").string(), model = (dir / "model").string();
  ptnet::testing::write_source(src, data);
  const std::string train = "train --data " + data + " --out " + model +
                            " --preset fast --channels 4,8,8 --hidden 16 --latent 16 --epochs 1 --batch 16"
                            " --samples-per-epoch 32 --val-samples 32 --threads 1 --lr 1e-9 --force";
  const std::string said = "train: warning: " + model + ": ";
  CmdResult r = run(train);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto line = r.err.find(said);
  ASSERT_NE(line, std::string::npos) << r.err;
  const auto start = line + said.size();
  const std::string warning = r.err.substr(start, r.err.find('\n', start) - start);
  EXPECT_EQ(warning.rfind("validation RMSE ", 0), 0u) << warning;
  EXPECT_NE(warning.find(" kPa is no better than the "), std::string::npos) << warning;
  EXPECT_NE(warning.find("all-zero baseline"), std::string::npos) << warning;
  EXPECT_NE(warning.find("copy baseline"), std::string::npos) << warning;

  r = run(train + " --strict");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("ptnet: error: " + model + ": " + warning + " (--strict; the folder is kept)\n"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(fs::path(model) / "model.pt"));

  r = run("evaluate --model " + model + " --data " + data + " --out " + (dir / "report").string() + " --threads 1");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("evaluate: warning: " + model + "/config.json: " + warning + "\n"), std::string::npos)
      << r.err;
  r = run("transfer --model " + model + " --in " + data + " --sequence m0__orig --target male,185,95 --out " +
          (dir / "t.npy").string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("transfer: warning: " + model + "/config.json: " + warning + "\n"), std::string::npos)
      << r.err;
  std::ifstream metrics(dir / "report" / "metrics.json"), page(dir / "report" / "index.html");
  const std::string m((std::istreambuf_iterator<char>(metrics)), {}), p((std::istreambuf_iterator<char>(page)), {});
  EXPECT_NE(m.find("\"warning\": \"" + warning + "\""), std::string::npos);
  EXPECT_NE(p.find("<p class=\"warning\">"), std::string::npos);

  // Outputs that exist are refused before the work, not after it: evaluate
  // before its pairs (it evaluated them all first), train before the ranks
  // meet (rank 0 waited --dist-timeout for rank 1 first).
  r = run("evaluate --model " + model + " --data " + data + " --out " + (dir / "report").string() + " --threads 1");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + (dir / "report" / "metrics.csv").string() + ": exists; pass --force to overwrite\n");
  const auto t = ptnet::testing_cli::run_program(
      PTNET_BINARY, "train --data " + data + " --out " + model + " --world-size 2 --rank 0 --dist-timeout 60"
                    " --rendezvous tcp://127.0.0.1:" + std::to_string(29400 + ::getpid() % 500),
      dir / "train", {}, "PTNET_DIST_TOKEN=check-before-work-token");
  EXPECT_EQ(t.status, 1);
  EXPECT_EQ(t.err, "ptnet: error: " + model + ": exists; pass --force to overwrite or --resume to continue\n");
  fs::remove_all(dir);
}

