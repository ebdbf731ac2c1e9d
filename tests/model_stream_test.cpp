// ptnet::Stream against the offline transfer on a recorded sequence: a
// one-frame model (the fast preset's frame network) equals Transfer::run on
// every frame; a window model's frame t is the last frame of the transfer of
// frames t-K+1 .. t alone, and its first window gives K frames at once.
// Non-finite frames are errors that leave the stream unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "data_test_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/stream.hpp"
#include "ptnet/transfer.hpp"
#include "support/memory_source.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
using namespace ptnet::testing;
using ptnet::testing_util::error_of;
using ptnet::testing_util::TempDir;

namespace {

// Stream and offline transfer run the same folded network, the stream one
// frame per forward pass, the transfer 64: their convolutions may sum in
// another order. Tolerance in kPa, relative to the sequence's peak; cells
// within it of the contact threshold may differ by the threshold itself.
constexpr float kStreamTolerance = 1e-4f;

class StreamTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("model_stream_test");
    src_ = new MemorySource(synth_source(3, 2, 70));
    TrainOptions frame = synth_options(1, Arch::frame, Align::zoom);  // window 1, contact head (the fast preset)
    frame.crop_rows = 0;
    train(*src_, dir_->file("frame"), frame);
    train(*src_, dir_->file("window"), synth_options(1));
  }
  static void TearDownTestSuite() {
    delete src_;
    delete dir_;
  }
  static inline TempDir* dir_ = nullptr;
  static inline MemorySource* src_ = nullptr;
  BodySpec female_{"f", Sex::female, 165, 60, "original"};
  BodySpec male_{"m", Sex::male, 185, 95, "original"};

  PressureSequence recording() const { return src_->read_all("m2__orig"); }
};

// Largest |a - b| over n values, and the largest |b|.
std::pair<float, float> diff(const float* a, const float* b, std::size_t n) {
  float d = 0, peak = 0;
  for (std::size_t i = 0; i < n; ++i) {
    d = std::max(d, std::abs(a[i] - b[i]));
    peak = std::max(peak, std::abs(b[i]));
  }
  return {d, peak};
}

}  // namespace

TEST_F(StreamTest, OneFrameModelEqualsOfflineTransferOnEveryFrame) {
  const PressureSequence rec = recording();
  TransferOptions raw;
  raw.raw = true;  // compare before the threshold; the thresholded run is checked below
  const PressureSequence offline = Transfer(dir_->file("frame"), raw).run(rec, female_, male_);
  StreamOptions so;
  so.raw = true;
  Stream live(dir_->file("frame"), female_, male_, so);
  ASSERT_EQ(live.max_output_frames(), 1);
  std::vector<float> out(std::size_t(live.frame_cells()));
  for (int t = 0; t < rec.frames(); ++t) {
    ASSERT_EQ(live.push(rec.frame(t), out.data()), 1) << "frame " << t;
    auto [d, peak] = diff(out.data(), offline.frame(t), out.size());
    EXPECT_LE(d, kStreamTolerance * std::max(1.0f, peak)) << "frame " << t;
  }
  EXPECT_EQ(live.frames_in(), rec.frames());
}

TEST_F(StreamTest, WindowModelGivesTheLastFrameOfItsCausalWindow) {
  const PressureSequence rec = recording();
  const Transfer offline(dir_->file("window"));
  Stream live(dir_->file("window"), female_, male_);
  const int k = live.max_output_frames(), cells = live.frame_cells();
  ASSERT_EQ(k, 30);
  std::vector<float> out(std::size_t(k) * std::size_t(cells));
  auto window_of = [&](int last) {  // frames last-K+1 .. last alone
    PressureSequence w(rec.mat, k, rec.fps);
    std::copy(rec.frame(last - k + 1), rec.frame(last + 1), w.kpa.begin());
    return offline.run(w, female_, male_);
  };
  for (int t = 0; t < rec.frames(); ++t) {
    const int ready = live.push(rec.frame(t), out.data());
    if (t < k - 1) {
      EXPECT_EQ(ready, 0) << "frame " << t;
    } else if (t == k - 1) {  // the first window: all its frames at once
      ASSERT_EQ(ready, k);
      const PressureSequence want = window_of(t);
      auto [d, peak] = diff(out.data(), want.kpa.data(), want.kpa.size());
      EXPECT_LE(d, kStreamTolerance * std::max(1.0f, peak));
    } else {
      ASSERT_EQ(ready, 1) << "frame " << t;
      if (t % 10 == 0 || t == rec.frames() - 1) {
        const PressureSequence want = window_of(t);
        auto [d, peak] = diff(out.data(), want.frame(k - 1), std::size_t(cells));
        EXPECT_LE(d, kStreamTolerance * std::max(1.0f, peak)) << "frame " << t;
      }
    }
  }
}

TEST_F(StreamTest, ThresholdAppliedAsOffline) {
  const PressureSequence rec = recording();
  const PressureSequence offline = Transfer(dir_->file("frame")).run(rec, female_, male_);
  Stream live(dir_->file("frame"), female_, male_);
  std::vector<float> out(std::size_t(live.frame_cells()));
  std::size_t zeros_live = 0, zeros_offline = 0;
  for (int t = 0; t < rec.frames(); ++t) {
    live.push(rec.frame(t), out.data());
    zeros_live += std::size_t(std::count(out.begin(), out.end(), 0.0f));
    zeros_offline += std::size_t(std::count(offline.frame(t), offline.frame(t) + out.size(), 0.0f));
  }
  // Cells within float rounding of the threshold may fall either side.
  EXPECT_NEAR(double(zeros_live), double(zeros_offline), 0.001 * double(offline.kpa.size()));
}

TEST_F(StreamTest, NonFiniteFrameIsAnErrorAndChangesNothing) {
  StreamOptions o;
  o.input_name = "live.f32";
  Stream live(dir_->file("frame"), female_, male_, o);
  std::vector<float> frame(std::size_t(live.frame_cells()), 1.0f), out(frame.size());
  live.push(frame.data(), out.data());
  frame[5] = std::nanf("");
  EXPECT_EQ(error_of([&] { live.push(frame.data(), out.data()); }),
            "live.f32: pressure frames: non-finite value (NaN or Inf) in frame 1");
  EXPECT_EQ(live.frames_in(), 1);
}

TEST_F(StreamTest, BodiesOutOfRangeAndMissingModelAreErrors) {
  BodySpec giant = male_;
  giant.height_cm = 400;
  EXPECT_NE(error_of([&] { Stream(dir_->file("frame"), female_, giant); }).find("target body"), std::string::npos);
  EXPECT_NE(error_of([&] { Stream(dir_->file("nothing"), female_, male_); }), "(no error)");
}
