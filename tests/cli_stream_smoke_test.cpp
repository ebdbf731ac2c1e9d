// ptnet stream end to end: raw and .npy frames give the same output, one
// frame out per frame in, equal to the offline transfer for a one-frame model;
// a short or malformed input is a one-line error; empty input is a clean exit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "cli_test_util.hpp"
#include "data_test_util.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/transfer.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
using namespace ptnet::testing;
using namespace ptnet::testing_cli;
using ptnet::testing_util::TempDir;

namespace {

class StreamCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("cli_stream_smoke_test");
    MemorySource src = synth_source(3, 2, 40);
    TrainOptions o = synth_options(1, Arch::frame, Align::zoom);  // the fast preset's network, small
    o.crop_rows = 0;
    train(src, dir_->file("model"), o);
    rec_ = new PressureSequence(src.read_all("m2__orig"));
    std::ofstream(dir_->file("rec.f32"), std::ios::binary)
        .write(reinterpret_cast<const char*>(rec_->kpa.data()), std::streamsize(rec_->kpa.size() * sizeof(float)));
    write_npy_sequence(dir_->file("rec.npy"), *rec_, false);
  }
  static void TearDownTestSuite() {
    delete rec_;
    delete dir_;
  }
  static std::string stream(const std::string& in_args) {
    return "--quiet stream --model '" + dir_->file("model") + "' --source female,165,60 --target male,185,95 " +
           in_args;
  }
  static inline TempDir* dir_ = nullptr;
  static inline PressureSequence* rec_ = nullptr;
};

std::vector<float> floats(const std::string& bytes) {
  std::vector<float> v(bytes.size() / sizeof(float));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
  return v;
}

}  // namespace

TEST_F(StreamCliTest, RawAndNpyGiveTheOfflineTransfer) {
  const RunResult raw = run_ptnet(stream("< '" + dir_->file("rec.f32") + "'"), dir_->file("raw"));
  ASSERT_EQ(raw.status, 0) << raw.err;
  EXPECT_EQ(raw.out.size(), rec_->kpa.size() * sizeof(float));  // one frame out per frame in
  const RunResult npy = run_ptnet(stream("--in '" + dir_->file("rec.npy") + "'"), dir_->file("npy"));
  ASSERT_EQ(npy.status, 0) << npy.err;
  EXPECT_EQ(npy.out, raw.out);
  const PressureSequence offline = Transfer(dir_->file("model"))
                                       .run(*rec_, BodySpec{"s", Sex::female, 165, 60}, BodySpec{"t", Sex::male, 185, 95});
  const std::vector<float> got = floats(raw.out);
  ASSERT_EQ(got.size(), offline.kpa.size());
  std::size_t far = 0;  // cells beyond the stream test's tolerance (model_stream_test: 1e-4 of the peak)
  for (std::size_t i = 0; i < got.size(); ++i)
    if (std::abs(got[i] - offline.kpa[i]) > 1e-3f) ++far;
  // Only cells within rounding of the contact threshold may fall on the other side.
  EXPECT_LE(far, got.size() / 1000) << far << " cells differ";
}

TEST_F(StreamCliTest, EmptyInputIsACleanExit) {
  const RunResult r = run_ptnet(stream("< /dev/null --stats"), dir_->file("empty"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(StreamCliTest, ShortFrameIsAOneLineError) {
  {
    std::ofstream f(dir_->file("short.f32"), std::ios::binary);
    f.write(reinterpret_cast<const char*>(rec_->kpa.data()), std::streamsize((2 * 16 * 8 + 25) * sizeof(float)));
  }
  const RunResult r = run_ptnet(stream("--in '" + dir_->file("short.f32") + "'"), dir_->file("short"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + dir_->file("short.f32") +
                       ": frame 2 is short: expected 512 bytes (16 x 8 float32), found 100\n");
  EXPECT_EQ(r.out.size(), 2u * 16 * 8 * sizeof(float));  // the complete frames were answered
}

TEST_F(StreamCliTest, MalformedNpyAndNonFiniteFramesAreErrors) {
  NpyArray wrong{{3, 8, 16}, std::vector<float>(3 * 8 * 16, 0.0f)};
  write_npy(dir_->file("wrong.npy"), wrong, false);
  RunResult r = run_ptnet(stream("--in '" + dir_->file("wrong.npy") + "'"), dir_->file("wrong"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + dir_->file("wrong.npy") + ": expected shape [T, 16, 8], found [3, 8, 16]\n");

  std::vector<float> bad(16 * 8, 1.0f);
  bad[3] = INFINITY;
  std::ofstream(dir_->file("inf.f32"), std::ios::binary)
      .write(reinterpret_cast<const char*>(bad.data()), std::streamsize(bad.size() * sizeof(float)));
  r = run_ptnet(stream("--in '" + dir_->file("inf.f32") + "'"), dir_->file("inf"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + dir_->file("inf.f32") +
                       ": pressure frames: non-finite value (NaN or Inf) in frame 0\n");

  r = run_ptnet(stream("--format npy --in '" + dir_->file("rec.f32") + "'"), dir_->file("notnpy"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("expected a .npy stream"), std::string::npos) << r.err;
}
