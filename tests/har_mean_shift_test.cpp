// Mean shift and its bandwidth rule on hand-made point sets.
#include <gtest/gtest.h>

#include <random>

#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

using namespace ptnet::har;

namespace {
// Two Gaussian blobs of `per` points in 2-D, centres (0,0) and (10,0), sd 0.5.
Eigen::MatrixXd two_blobs(int per, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 0.5);
  Eigen::MatrixXd x(2 * per, 2);
  for (int i = 0; i < 2 * per; ++i) {
    x(i, 0) = (i < per ? 0.0 : 10.0) + g(rng);
    x(i, 1) = g(rng);
  }
  return x;
}
}  // namespace

TEST(HarMeanShift, TwoSeparatedBlobsAreTwoClusters) {
  const Eigen::MatrixXd x = two_blobs(300, 7);
  MeanShiftResult r = mean_shift(x, {});
  ASSERT_EQ(r.clusters(), 2);
  EXPECT_EQ(r.sizes[0] + r.sizes[1], 600);
  // Every point of a blob carries its blob's label.
  for (int i = 1; i < 300; ++i) EXPECT_EQ(r.labels[i], r.labels[0]);
  for (int i = 301; i < 600; ++i) EXPECT_EQ(r.labels[i], r.labels[300]);
  EXPECT_NE(r.labels[0], r.labels[300]);
  // Modes near the blob centres.
  const int a = r.labels[0], b = r.labels[300];
  EXPECT_NEAR(r.modes(a, 0), 0.0, 0.3);
  EXPECT_NEAR(r.modes(b, 0), 10.0, 0.3);
  // Labels agree with nearest-mode assignment (how test windows are labelled).
  EXPECT_EQ(assign_nearest(r.modes, x), r.labels);
}

TEST(HarMeanShift, GaussianKernelAlsoFindsTwo) {
  MeanShiftOptions o;
  o.kernel = Kernel::gaussian;
  MeanShiftResult r = mean_shift(two_blobs(200, 3), o);
  EXPECT_EQ(r.clusters(), 2);
}

TEST(HarMeanShift, BandwidthRuleIsDeterministicAndMatchesHandComputation) {
  const Eigen::MatrixXd x = two_blobs(500, 11);
  const double h1 = estimate_bandwidth(x, 0.3);
  const double h2 = estimate_bandwidth(x, 0.3);
  EXPECT_EQ(h1, h2);  // bit for bit
  EXPECT_EQ(mean_shift(x, {}).bandwidth, h1);
  // Points 0, 1, 3 on a line: with quantile 1 (farthest other point) the
  // distances are 3, 2, 3 -> mean 8/3; with quantile 0.5 (k = 1, nearest)
  // they are 1, 1, 2 -> mean 4/3.
  Eigen::MatrixXd line(3, 1);
  line << 0, 1, 3;
  EXPECT_NEAR(estimate_bandwidth(line, 1.0), 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(estimate_bandwidth(line, 0.5), 4.0 / 3.0, 1e-12);
}

TEST(HarMeanShift, TinyClusterMergesIntoNearestLargerOne) {
  // 200 points at 0, 200 at 10, 1 outlier at 30 (0.25 % < 1 %).
  Eigen::MatrixXd x(401, 1);
  for (int i = 0; i < 200; ++i) x(i, 0) = 0.01 * (i % 10);
  for (int i = 200; i < 400; ++i) x(i, 0) = 10 + 0.01 * (i % 10);
  x(400, 0) = 30;
  MeanShiftOptions o;
  o.bandwidth = 2;
  MeanShiftResult r = mean_shift(x, o);
  ASSERT_EQ(r.clusters(), 2);
  EXPECT_EQ(r.labels[400], r.labels[200]);  // joined the nearer blob
  o.min_cluster_fraction = 0;               // without the rule it stays alone
  EXPECT_EQ(mean_shift(x, o).clusters(), 3);
}

TEST(HarMeanShift, BadInputIsAnError) {
  Eigen::MatrixXd one(1, 2);
  one << 1, 2;
  EXPECT_THROW(estimate_bandwidth(one), ptnet::Error);
  EXPECT_THROW(estimate_bandwidth(two_blobs(5, 1), 0.0), ptnet::Error);
  Eigen::MatrixXd nan = two_blobs(5, 1);
  nan(2, 1) = std::nan("");
  EXPECT_THROW(mean_shift(nan, {}), ptnet::Error);
  try {
    mean_shift(Eigen::MatrixXd(0, 2), {});
    FAIL();
  } catch (const ptnet::Error& e) {
    EXPECT_STREQ(e.what(), "mean shift: no points to cluster");
  }
}
