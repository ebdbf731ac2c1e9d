// What is loaded is verified: the zip CRC-32s of model.pt and checkpoint.pt,
// the digest of the weights recorded in config.json (transfer, --init,
// --resume), config.json's numbers and window, and the frame rate of the
// data against the model's. Every mismatch is one line naming the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli_test_util.hpp"
#include "core/zip_check.hpp"
#include "data_test_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model.hpp"
#include "ptnet/transfer.hpp"
#include "support/memory_source.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
using namespace ptnet::testing;
namespace fs = std::filesystem;
using ptnet::testing_cli::slurp;
using ptnet::testing_util::error_of;

namespace {

class IntegrityTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp_ = new testing_util::TempDir("model_integrity");
    base_ = temp_->path;
    src_ = new MemorySource(synth_source(3, 2, 90));
    train(*src_, (base_ / "model").string(), synth_options(2));
  }
  static void TearDownTestSuite() {
    delete temp_;  // removes the folder
    delete src_;
  }
  static fs::path copy_model(const std::string& name) {
    const fs::path p = base_ / name;
    fs::remove_all(p);
    fs::copy(base_ / "model", p);
    return p;
  }
  // Flips `n` bytes in the middle of the file (inside tensor data).
  static void flip_bytes(const fs::path& p, int n) {
    std::string b = slurp(p);
    for (int i = 0; i < n; ++i) b[b.size() / 2 + std::size_t(i)] ^= 0x5a;
    std::ofstream(p, std::ios::binary | std::ios::trunc) << b;
  }
  static inline testing_util::TempDir* temp_ = nullptr;
  static inline fs::path base_;
  static inline MemorySource* src_ = nullptr;
};

}  // namespace

TEST_F(IntegrityTest, ConfigRecordsTheDigestsOfWhatWasWritten) {
  const ModelDir d = read_model_dir((base_ / "model").string());
  int epoch = -1;
  EXPECT_EQ(recorded_digest(d, "model.pt").size(), 16u);
  EXPECT_EQ(recorded_digest(d, "checkpoint.pt", &epoch).size(), 16u);
  EXPECT_EQ(epoch, 2);
  PressureTransferNet net(d.model);
  load_weights(net, (base_ / "model" / "model.pt").string());
  EXPECT_EQ(weights_digest(*net), recorded_digest(d, "model.pt"));
  EXPECT_GT(verify_zip_file((base_ / "model" / "model.pt").string()), 3);
}

TEST_F(IntegrityTest, FlippedBytesFailTheArchiveCrc) {
  const fs::path p = copy_model("flipped");
  flip_bytes(p / "model.pt", 50);
  const std::string e = error_of([&] { Transfer(p.string()); });
  EXPECT_EQ(e.rfind((p / "model.pt").string() + ": damaged archive: record '", 0), 0u) << e;
  EXPECT_NE(e.find("fails its CRC-32 check"), std::string::npos) << e;
  // --init refuses it as well.
  TrainOptions o = synth_options(1);
  o.init = p.string();
  EXPECT_NE(error_of([&] { train(*src_, (base_ / "init_out").string(), o); }).find("fails its CRC-32 check"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(base_ / "init_out"));  // a failed fresh run leaves nothing
}

TEST_F(IntegrityTest, ReplacedWeightsFailTheDigest) {
  const fs::path p = copy_model("replaced");
  const ModelDir d = read_model_dir(p.string());
  torch::manual_seed(99);
  PressureTransferNet other(d.model);  // a valid archive of other weights
  fs::remove(p / "model.pt");
  save_weights(other, (p / "model.pt").string());
  const std::string e = error_of([&] { Transfer(p.string()); });
  EXPECT_EQ(e.rfind((p / "model.pt").string() + ": weights do not match the digest in " +
                        (p / "config.json").string(),
                    0),
            0u)
      << e;
  EXPECT_NE(e.find("corrupt or replaced file"), std::string::npos);
  TrainOptions o = synth_options(1);
  o.init = p.string();
  EXPECT_NE(error_of([&] { train(*src_, (base_ / "init_out2").string(), o); }).find("weights do not match"),
            std::string::npos);
}

TEST_F(IntegrityTest, ResumeVerifiesTheCheckpoint) {
  const fs::path p = copy_model("resume");
  flip_bytes(p / "checkpoint.pt", 50);
  TrainOptions o = synth_options(3);
  o.resume = true;
  const std::string e = error_of([&] { train(*src_, p.string(), o); });
  EXPECT_EQ(e.rfind((p / "checkpoint.pt").string() + ": damaged archive:", 0), 0u) << e;
  // A valid checkpoint of other weights: the digest catches it.
  const fs::path q = copy_model("resume2");
  auto j = nlohmann::json::parse(slurp(q / "config.json"));
  j["integrity"]["checkpoint.pt"]["digest"] = "0123456789abcdef";
  std::ofstream(q / "config.json") << j.dump();
  EXPECT_NE(error_of([&] { train(*src_, q.string(), o); }).find("checkpoint.pt: weights do not match the digest"),
            std::string::npos);
}

TEST_F(IntegrityTest, ConfigNumbersAreCheckedInOneLine) {
  const fs::path p = copy_model("config");
  const std::string cfg = slurp(p / "config.json");
  const std::string config = (p / "config.json").string();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = cfg;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    std::ofstream(p / "config.json", std::ios::trunc) << text;
    return error_of([&] { read_model_dir(p.string()); });
  };
  // dump(2) sorts the keys: the top-level window is last, the architecture's last in its block.
  EXPECT_EQ(with("\"fps\": 30.0", "\"fps\": 1e400"), config + ": not valid JSON (number overflow parsing '1e400')");
  EXPECT_EQ(with("\"window\": 30\n}", "\"window\": 0\n}"), config + ": window 0 disagrees with the architecture's 30");
  EXPECT_EQ(with("\"window\": 30\n}", "\"window\": -30\n}"),
            config + ": window -30 disagrees with the architecture's 30");
  EXPECT_EQ(with("\"window\": 30\n  }", "\"window\": 1e10\n  }"),
            config + ": field \"window\": expected an integer, found '10000000000.0'");
  EXPECT_EQ(with("\"window\": 30\n  }", "\"window\": 0\n  }"), config + ": model: window must be in 1-10000, found 0");
  EXPECT_EQ(with("\"fps\": 30.0", "\"fps\": 0.0"), config + ": fps 0 is not in [1, 1000]");
}

TEST_F(IntegrityTest, AFrameRateMismatchIsAnError) {
  Transfer net((base_ / "model").string());
  PressureSequence s = synth_sequence(0, src_->bodies()[0], 60, src_->mat());
  s.fps = 60;
  EXPECT_EQ(error_of([&] { net.run(s, src_->bodies()[0], src_->bodies()[1]); }),
            (base_ / "model").string() +
                ": model is trained at 30 fps, the sequence is at 60 fps (simulate the data again "
                "with fps 30)");
  // Fine-tuning on 60 fps data from a 30 fps model.
  MemorySource fast(src_->mat(), 60, "fast60");
  for (const auto& b : src_->bodies()) fast.add_body(b);
  for (const auto& m : src_->sequences()) {
    PressureSequence q = src_->read_all(m.name);
    q.fps = 60;
    fast.add_sequence(m, q);
  }
  TrainOptions o = synth_options(1);
  o.init = (base_ / "model").string();
  EXPECT_EQ(error_of([&] { train(fast, (base_ / "ft60").string(), o); }), "fast60: is at 60 fps, the model at 30 fps");
}

TEST(ZipCheck, TruncatedOrForeignArchivesAreNamed) {
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);  // the standard check value
  try {
    verify_zip(std::string(100, 'x'), "m.pt");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "m.pt: damaged archive: no end-of-central-directory record (truncated, or not a zip archive)");
  }
}

// config.json's validation metrics against the all-zero and copy baselines
// (baseline_warning): a model must beat each by kBaselineMargin; a baseline
// of RMSE 0 (identity pairs' copy) is no bar; older metrics without the
// figures say nothing.
TEST(BaselineWarning, BothFiguresNamedWhenNoBetter) {
  const auto metrics = [](double model, double zero, double copy) {
    return nlohmann::json{{"val_rmse_kpa", model}, {"val_rmse_zero_kpa", zero}, {"val_rmse_copy_kpa", copy}};
  };
  EXPECT_EQ(baseline_warning(metrics(13.82, 13.82, 15.104)),
            "validation RMSE 13.820 kPa is no better than the all-zero baseline's 13.820 kPa (copy baseline "
            "15.104 kPa)");
  EXPECT_EQ(baseline_warning(metrics(6.0, 13.82, 6.02)),
            "validation RMSE 6.000 kPa is no better than the copy baseline's 6.020 kPa (all-zero baseline "
            "13.820 kPa)");
  EXPECT_EQ(baseline_warning(metrics(5.0, 13.82, 6.02)), "");
  EXPECT_EQ(baseline_warning(metrics(5.0, 13.82, 0.0)), "");  // identity pairs: the copy is the truth
  EXPECT_EQ(baseline_warning(nlohmann::json{{"val_rmse_kpa", 5.0}}), "");
}
