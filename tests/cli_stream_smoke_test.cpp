// ptnet stream end to end: raw and .npy frames give the same output, one
// frame out per frame in, equal to the offline transfer for a one-frame model;
// a short or malformed input is a one-line error; empty input is a clean exit.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <thread>

#include "cli_test_util.hpp"
#include "core/npy_internal.hpp"
#include "data_test_util.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/transfer.hpp"
#include "support/memory_source.hpp"
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
    train(synth_source(3, 2, 90), dir_->file("window_model"), synth_options(1));  // a 30-frame window network
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

// A window model answers once its window is full: fewer frames than the
// window transfer nothing, which is an error, not a silent empty output.
TEST_F(StreamCliTest, FewerFramesThanTheWindowIsAnError) {
  const std::size_t frame_bytes = std::size_t(rec_->mat.cells()) * sizeof(float);
  const auto frames = [&](int n) {
    const std::string path = dir_->file(std::to_string(n) + ".f32");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(rec_->kpa.data()), std::streamsize(n * frame_bytes));
    return path;
  };
  const std::string window = "--quiet stream --model '" + dir_->file("window_model") +
                             "' --source female,165,60 --target male,185,95 --in ";
  RunResult r = run_ptnet(window + "'" + frames(29) + "'", dir_->file("w29"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + frames(29) + ": 29 frames, fewer than the model's window of 30: "
                   "no frame was transferred\n");
  EXPECT_TRUE(r.out.empty());
  r = run_ptnet(window + "'" + frames(30) + "'", dir_->file("w30"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.size(), 30 * frame_bytes);
}

// An .npy stream holds the frames its header announces: more is an error
// (after the announced ones are answered), as fewer is.
TEST_F(StreamCliTest, DataBeyondTheNpyHeaderIsAnError) {
  const std::size_t frame_bytes = std::size_t(rec_->mat.cells()) * sizeof(float);
  const std::string path = dir_->file("long.npy");
  PressureSequence two(rec_->mat, 2, rec_->fps);
  std::copy(rec_->kpa.begin(), rec_->kpa.begin() + std::ptrdiff_t(two.kpa.size()), two.kpa.begin());
  write_npy_sequence(path, two, true);
  std::ofstream(path, std::ios::binary | std::ios::app)
      .write(reinterpret_cast<const char*>(rec_->kpa.data()), std::streamsize(frame_bytes));  // a third frame
  const RunResult r = run_ptnet(stream("--in '" + path + "'"), dir_->file("long"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + path + ": more data after the 2 frames the npy header promises\n");
  EXPECT_EQ(r.out.size(), 2 * frame_bytes);
}

// Stopped by Ctrl-C or SIGTERM while its input is still open, the stream
// prints its --stats for the frames it answered, then dies of the signal.
TEST_F(StreamCliTest, StatsArePrintedWhenStoppedBySignal) {
  const std::size_t frame_bytes = std::size_t(rec_->mat.cells()) * sizeof(float);
  for (int sig : {SIGINT, SIGTERM}) {
    const std::string fifo = dir_->file("live" + std::to_string(sig)), out = fifo + ".out", err = fifo + ".err";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const pid_t p = spawn_ptnet(stream("--stats --in '" + fifo + "'"), err, "", out);
    // The writing end, once the stream has opened the reading one (at most 90 s).
    int writer = -1;
    for (int i = 0; i < 900 && writer < 0; ++i) {
      writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (writer < 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ASSERT_GE(writer, 0) << slurp(err);
    ASSERT_EQ(::write(writer, rec_->kpa.data(), 3 * frame_bytes), ssize_t(3 * frame_bytes));
    for (int i = 0; i < 900 && std::filesystem::file_size(out) < 3 * frame_bytes; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ::kill(p, sig);
    const int status = wait_within(p, 90);
    ::close(writer);
    EXPECT_EQ(status, 128 + sig) << slurp(err);
    EXPECT_EQ(std::filesystem::file_size(out), 3 * frame_bytes);
    EXPECT_NE(slurp(err).find("stream: 3 frames, per-frame latency p50 "), std::string::npos)
        << "signal " << sig << ": " << slurp(err);
  }
}
