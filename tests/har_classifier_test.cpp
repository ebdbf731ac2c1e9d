// The CNN classifier learns an easy task and is deterministic.
#include <gtest/gtest.h>

#include <random>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

using namespace ptnet::har;

namespace {
// Windows [n, 10, 20, 12] with a 3 x 3 blob of ~20 kPa on the left half
// (label 0) or the right half (label 1) at a random place, plus noise.
WindowBatch blobs(int n, std::uint64_t seed, std::vector<int>& labels) {
  WindowBatch b;
  b.mat = ptnet::MatSpec{20, 12, 0.02};
  b.frames = 10;
  b.kpa.assign(std::size_t(n) * b.frames * b.mat.cells(), 0.0f);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> row(0, 16), col(0, 2), side(0, 1);
  std::normal_distribution<float> noise(0, 1);
  labels.clear();
  for (int i = 0; i < n; ++i) {
    const int l = side(rng);
    labels.push_back(l);
    const int r0 = row(rng), c0 = col(rng) + (l ? 7 : 0);
    float* w = b.kpa.data() + std::size_t(i) * b.frames * b.mat.cells();
    for (int t = 0; t < b.frames; ++t)
      for (int r = 0; r < 20; ++r)
        for (int c = 0; c < 12; ++c) {
          float v = std::max(0.0f, noise(rng));
          if (r >= r0 && r < r0 + 3 && c >= c0 && c < c0 + 3) v += 20;
          w[t * 240 + r * 12 + c] = v;
        }
  }
  return b;
}
}  // namespace

TEST(HarClassifier, LearnsLeftBlobVersusRightBlob) {
  std::vector<int> train_labels, test_labels;
  InputOptions in;
  in.time_blocks = 2;
  in.pool = 2;
  const PreparedWindows train = prepare_windows(blobs(240, 1, train_labels), in);
  const PreparedWindows test = prepare_windows(blobs(100, 2, test_labels), in);
  ASSERT_EQ(train.channels, 2);
  ASSERT_EQ(train.rows, 10);
  ASSERT_EQ(train.cols, 6);
  ClassifierOptions o;
  o.epochs = 8;
  o.batch_size = 32;
  WindowClassifier net(train.channels, train.rows, train.cols, 2, o);
  net.train(train, train_labels);
  const std::vector<int> pred = net.predict(test);
  const ClassificationReport r = classification_report(test_labels, pred, 2);
  EXPECT_GE(r.accuracy, 0.95);
  EXPECT_GE(r.macro_f1, 0.95);

  // Same seed, same predictions.
  WindowClassifier again(train.channels, train.rows, train.cols, 2, o);
  again.train(train, train_labels);
  EXPECT_EQ(again.predict(test), pred);

  // Probabilities: rows of 2 that sum to 1, their argmax the prediction. A
  // float32 softmax of 2 logits: exp, one sum and two divisions, each
  // rounded within eps = 1.2e-7, so a row sums to 1 within ~4 eps = 5e-7
  // on any CPU's kernels; 1e-5 leaves a factor 20.
  const std::vector<float> p = net.probabilities(test);
  ASSERT_EQ(p.size(), 2u * 100);
  for (int i = 0; i < 100; ++i) {
    EXPECT_NEAR(p[2 * i] + p[2 * i + 1], 1.0f, 1e-5f);
    EXPECT_GE(p[2 * i], 0.0f);
  }
  EXPECT_EQ(argmax_rows(p, 2), pred);
}

TEST(HarClassifier, ArgmaxRowsTakesTheFirstLargestScore) {
  EXPECT_EQ(argmax_rows({0.1f, 0.7f, 0.2f, 0.5f, 0.5f, 0.0f}, 3), (std::vector<int>{1, 0}));
  EXPECT_TRUE(argmax_rows({}, 3).empty());
  EXPECT_THROW(argmax_rows({1, 2, 3, 4}, 3), ptnet::Error);
  EXPECT_THROW(argmax_rows({1, 2}, 0), ptnet::Error);
}

TEST(HarClassifier, InputsAreBlockAveragedLog1p) {
  WindowBatch b;
  b.mat = ptnet::MatSpec{4, 4, 0.02};
  b.frames = 4;
  b.kpa.assign(4 * 16, 0.0f);
  for (int t = 0; t < 2; ++t) b.kpa[t * 16 + 0] = 8.0f;  // cell (0,0) frames 0-1
  InputOptions in;
  in.time_blocks = 2;
  in.pool = 2;
  const PreparedWindows p = prepare_windows(b, in);
  ASSERT_EQ(p.values.size(), 2u * 2 * 2);
  EXPECT_NEAR(p.values[0], std::log1p(8.0 / 4.0), 1e-6);  // mean over 2 frames x 4 cells
  for (std::size_t i = 1; i < p.values.size(); ++i) EXPECT_EQ(p.values[i], 0.0f);
}

TEST(HarClassifier, BadInputIsAnError) {
  ClassifierOptions o;
  EXPECT_THROW(WindowClassifier(2, 4, 4, 1, o), ptnet::Error);
  WindowClassifier net(2, 4, 4, 2, o);
  PreparedWindows wrong;
  wrong.channels = 3;
  wrong.rows = 4;
  wrong.cols = 4;
  wrong.values.assign(48, 0.0f);
  try {
    net.train(wrong, {0});
    FAIL();
  } catch (const ptnet::Error& e) {
    EXPECT_STREQ(e.what(), "har: classifier expects windows of 2x4x4, found 3x4x4");
  }
  o.device = "tpu";
  EXPECT_THROW(WindowClassifier(2, 4, 4, 2, o), ptnet::Error);
}
