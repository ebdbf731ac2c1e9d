// ptnet::Transfer on a tiny trained model: any length >= window, overlapped
// windows averaged, and clear errors for bad model folders and inputs; the
// .npy reader/writer.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "core/npy_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/transfer.hpp"
#include "support/memory_source.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
using namespace ptnet::testing;
namespace fs = std::filesystem;

namespace {

class TransferTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ptnet_model_transfer_test_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    src_ = new MemorySource(synth_source(3, 2, 90));
    train(*src_, dir_.string(), synth_options(1));
  }
  static void TearDownTestSuite() {
    fs::remove_all(dir_);
    delete src_;
  }
  static std::string expect_error(const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
  }
  // A copy of the model folder that a test may damage.
  static fs::path copy_model(const std::string& name) {
    fs::path p = fs::temp_directory_path() / ("ptnet_model_transfer_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(p);
    fs::copy(dir_, p);
    return p;
  }
  static inline fs::path dir_;
  static inline MemorySource* src_ = nullptr;
  BodySpec female_{"f", Sex::female, 165, 60, "original"};
  BodySpec male_{"m", Sex::male, 185, 95, "original"};
};

}  // namespace

TEST_F(TransferTest, AnyLengthFromTheWindowUp) {
  Transfer net(dir_.string());
  EXPECT_EQ(net.model().model.window, 30);
  for (int frames : {30, 31, 47, 90}) {
    PressureSequence in = synth_sequence(0, female_, frames, src_->mat());
    PressureSequence out = net.run(in, female_, male_);
    ASSERT_EQ(out.frames(), frames);
    EXPECT_EQ(out.mat, in.mat);
    for (float v : out.kpa) ASSERT_TRUE(v >= 0 && std::isfinite(v));
  }
}

TEST_F(TransferTest, OverlappingWindowsAreAveraged) {
  // With stride 1 every frame is covered by all windows containing it; the
  // first 30 frames of a 30-frame input equal one forward pass, and frame 0
  // of a longer input (covered only by the first window) matches it.
  TransferOptions one;
  one.stride = 1;
  Transfer net(dir_.string(), one);
  PressureSequence in = synth_sequence(1, female_, 40, src_->mat());
  PressureSequence head = in;
  head.kpa.resize(std::size_t(30) * in.mat.cells());
  PressureSequence a = net.run(in, female_, male_), b = net.run(head, female_, male_);
  for (int c = 0; c < in.mat.cells(); ++c) EXPECT_NEAR(a.frame(0)[c], b.frame(0)[c], 1e-4);
}

TEST_F(TransferTest, ContactThresholdZeroesOnlyWeakCells) {
  // Training fits the output activation threshold from its candidates.
  const double fitted = read_model_dir(dir_.string()).norm.contact_threshold_kpa;
  EXPECT_GE(fitted, kContactKpa);
  EXPECT_LE(fitted, 40.0);

  // A folder whose threshold is the median non-zero raw output: thresholded
  // output = raw where raw >= t, else 0; both sides of t occur.
  TransferOptions raw_opt;
  raw_opt.raw = true;
  PressureSequence in = synth_sequence(2, female_, 45, src_->mat());
  const PressureSequence raw = Transfer(dir_.string(), raw_opt).run(in, female_, male_);
  std::vector<float> positive;
  for (float v : raw.kpa)
    if (v > 0) positive.push_back(v);
  ASSERT_GT(positive.size(), 10u);
  std::nth_element(positive.begin(), positive.begin() + positive.size() / 2, positive.end());
  const float t = positive[positive.size() / 2];
  fs::path p = copy_model("threshold");
  auto j = nlohmann::json::parse(std::ifstream(p / "config.json"));
  j["normalisation"]["contact_threshold_kpa"] = t;
  std::ofstream(p / "config.json") << j.dump();
  const PressureSequence cut = Transfer(p.string()).run(in, female_, male_);
  int zeroed = 0, kept = 0;
  for (std::size_t i = 0; i < raw.kpa.size(); ++i) {
    if (raw.kpa[i] >= t) {
      ASSERT_EQ(cut.kpa[i], raw.kpa[i]);
      ++kept;
    } else {
      ASSERT_EQ(cut.kpa[i], 0.0f);
      zeroed += raw.kpa[i] > 0;
    }
  }
  EXPECT_GT(zeroed, 0);
  EXPECT_GT(kept, 0);
  j["normalisation"]["contact_threshold_kpa"] = -1;
  std::ofstream(p / "config.json") << j.dump();
  EXPECT_EQ(expect_error([&] { Transfer(p.string()); }),
            (p / "config.json").string() + ": normalisation.contact_threshold_kpa must be >= 0");
  fs::remove_all(p);
}

TEST_F(TransferTest, MirrorAveragingMakesTheTransferMirrorSymmetric) {
  // ModelConfig::mirror: the transfer of a left-right mirrored recording is
  // the mirrored transfer (float rounding apart). The same weights without it
  // are not symmetric, so the property comes from the averaging.
  const auto mirrored = [](PressureSequence s) {
    for (int t = 0; t < s.frames(); ++t)
      for (int r = 0; r < s.mat.rows; ++r) std::reverse(&s.at(t, r, 0), &s.at(t, r, 0) + s.mat.cols);
    return s;
  };
  const auto asymmetry = [&](const Transfer& net) {
    const PressureSequence in = synth_sequence(1, female_, 40, src_->mat());
    const PressureSequence a = mirrored(net.run(in, female_, male_)), b = net.run(mirrored(in), female_, male_);
    double worst = 0, peak = 0;
    for (std::size_t i = 0; i < a.kpa.size(); ++i) {
      worst = std::max(worst, double(std::abs(a.kpa[i] - b.kpa[i])));
      peak = std::max(peak, double(a.kpa[i]));
    }
    EXPECT_GT(peak, 1.0);
    return worst / peak;
  };
  fs::path p = copy_model("mirror");
  auto j = nlohmann::json::parse(std::ifstream(p / "config.json"));
  ASSERT_FALSE(j["architecture"]["mirror"].get<bool>());
  j["architecture"]["mirror"] = true;
  std::ofstream(p / "config.json") << j.dump();
  EXPECT_GT(asymmetry(Transfer(dir_.string())), 1e-2);
  EXPECT_LT(asymmetry(Transfer(p.string())), 1e-5);
  fs::remove_all(p);
}

TEST_F(TransferTest, BadInputsAreClearErrors) {
  Transfer net(dir_.string());
  PressureSequence short_seq = synth_sequence(0, female_, 20, src_->mat());
  EXPECT_EQ(expect_error([&] { net.run(short_seq, female_, male_); }),
            "transfer: sequence has 20 frames, the model's window needs at least 30");
  PressureSequence other_mat = synth_sequence(0, female_, 40, MatSpec{80, 28, 0.02});
  EXPECT_EQ(expect_error([&] { net.run(other_mat, female_, male_); }),
            dir_.string() + ": model is built for a 16 x 8 mat, the sequence has 80 x 28");
  BodySpec giant = male_;
  giant.height_cm = 300;
  PressureSequence ok = synth_sequence(0, female_, 40, src_->mat());
  EXPECT_EQ(expect_error([&] { net.run(ok, female_, giant); }), "target body: height_cm 300 outside 100-230");
  BodySpec light = female_;
  light.weight_kg = 5;
  EXPECT_EQ(expect_error([&] { net.run(ok, light, male_); }), "source body: weight_kg 5 outside 20-250");
}

TEST_F(TransferTest, BrokenModelFoldersAreClearErrors) {
  EXPECT_EQ(expect_error([] { Transfer("/nonexistent/model"); }), "/nonexistent/model: no such model folder");
  fs::path p = copy_model("nocfg");
  fs::remove(p / "config.json");
  EXPECT_NE(expect_error([&] { Transfer(p.string()); }).find("config.json: no such file"), std::string::npos);
  std::ofstream(p / "config.json") << "{ not json";
  EXPECT_NE(expect_error([&] { Transfer(p.string()); }).find("config.json: not valid JSON"), std::string::npos);
  std::ofstream(p / "config.json") << R"({"format": "ptnet-model", "version": 1})";
  EXPECT_EQ(expect_error([&] { Transfer(p.string()); }),
            (p / "config.json").string() + ": missing field \"architecture\"");
  fs::remove_all(p);

  p = copy_model("badweights");
  std::ofstream(p / "model.pt") << "truncated";
  EXPECT_EQ(expect_error([&] { Transfer(p.string()); }),
            (p / "model.pt").string() + ": damaged archive: too short for a zip archive (9 bytes)");
  fs::remove(p / "model.pt");
  EXPECT_EQ(expect_error([&] { Transfer(p.string()); }), (p / "model.pt").string() + ": no such file (model weights)");
  fs::remove_all(p);

  // config.json claiming another window than the weights were built for.
  p = copy_model("window");
  auto j = nlohmann::json::parse(std::ifstream(p / "config.json"));
  j["architecture"]["window"] = 20;
  j["window"] = 20;
  std::ofstream(p / "config.json") << j.dump();
  EXPECT_NE(expect_error([&] { Transfer(p.string()); }).find("the model expects [4, 20, 3, 3]"), std::string::npos);
  fs::remove_all(p);
}

TEST(Npy, RoundTripAndValidation) {
  fs::path dir = fs::temp_directory_path() / ("ptnet_npy_test_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  MatSpec mat{5, 3, 0.02};
  PressureSequence s(mat, 4, 30);
  for (std::size_t i = 0; i < s.kpa.size(); ++i) s.kpa[i] = 0.5f * float(i);
  const std::string path = (dir / "x.npy").string();
  write_npy_sequence(path, s, false);
  EXPECT_THROW(write_npy_sequence(path, s, false), Error);  // no clobbering
  PressureSequence back = read_npy_sequence(path, mat, 30);
  EXPECT_EQ(back.kpa, s.kpa);
  // Header is 64-byte aligned, version 1.0.
  std::ifstream f(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(f), {}};
  EXPECT_EQ((bytes.size() - s.kpa.size() * 4) % 64, 0u);
  EXPECT_NE(bytes.find("'shape': (4, 5, 3)"), std::string::npos);
  try {
    read_npy_sequence(path, MatSpec{80, 28, 0.02}, 30);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": expected shape [T, 80, 28], found [4, 5, 3]");
  }
  std::string f8 = bytes;
  f8.replace(f8.find("<f4"), 3, "<f8");
  std::ofstream((dir / "f8.npy").string(), std::ios::binary) << f8;
  try {
    read_npy((dir / "f8.npy").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("expected dtype float32 ('<f4'), found '<f8'"), std::string::npos);
  }
  std::ofstream((dir / "cut.npy").string(), std::ios::binary) << bytes.substr(0, bytes.size() - 4);
  EXPECT_THROW(read_npy((dir / "cut.npy").string()), Error);
  fs::remove_all(dir);
}
