// Mean shift, its bandwidth rule and the clustering metrics on hand-made point sets.
#include <gtest/gtest.h>

#include <random>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

using namespace ptnet::har;

namespace {
// Gaussian blobs of `per` points each around the rows of centres [B, D], sd
// 0.5; blob b in rows [b * per, (b + 1) * per).
Eigen::MatrixXd blobs(const Eigen::MatrixXd& centres, int per, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 0.5);
  Eigen::MatrixXd x(centres.rows() * per, centres.cols());
  for (int i = 0; i < x.rows(); ++i)
    for (int j = 0; j < x.cols(); ++j) x(i, j) = centres(i / per, j) + g(rng);
  return x;
}

// Two blobs in 2-D, centres (0,0) and (10,0).
Eigen::MatrixXd two_blobs(int per, std::uint64_t seed) {
  Eigen::MatrixXd c(2, 2);
  c << 0, 0, 10, 0;
  return blobs(c, per, seed);
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
  MeanShiftOptions single;
  single.quantiles = {0.3};  // one candidate: that quantile, no selection
  EXPECT_EQ(mean_shift(x, single).bandwidth, h1);
  EXPECT_EQ(mean_shift(x, single).quantile, 0.3);
  // Points 0, 1, 3 on a line: with quantile 1 (farthest other point) the
  // distances are 3, 2, 3 -> mean 8/3; with quantile 0.5 (k = 1, nearest)
  // they are 1, 1, 2 -> mean 4/3.
  Eigen::MatrixXd line(3, 1);
  line << 0, 1, 3;
  EXPECT_NEAR(estimate_bandwidth(line, 1.0), 8.0 / 3.0, 1e-12);
  EXPECT_NEAR(estimate_bandwidth(line, 0.5), 4.0 / 3.0, 1e-12);
}

namespace {
// Four blobs in 3-D at the corners of a square of side 10 (z = 0).
Eigen::MatrixXd four_blobs(int per, std::uint64_t seed) {
  Eigen::MatrixXd c(4, 3);
  c << 0, 0, 0, 10, 0, 0, 0, 10, 0, 10, 10, 0;
  return blobs(c, per, seed);
}

std::vector<int> blob_of(int blobs, int per) {
  std::vector<int> v;
  for (int i = 0; i < blobs * per; ++i) v.push_back(i / per);
  return v;
}
}  // namespace

TEST(HarMeanShift, BandwidthRuleFindsFourBlobsWhereQuantilePointThreeFindsFewer) {
  const Eigen::MatrixXd x = four_blobs(150, 5);
  const std::vector<int> truth = blob_of(4, 150);
  // scikit-learn's single quantile 0.3: the 30 %-nearest neighbour of a
  // point lies in another blob (each holds 25 %), so the bandwidth spans
  // blobs and their modes merge.
  MeanShiftOptions single;
  single.quantiles = {0.3};
  EXPECT_LT(mean_shift(x, single).clusters(), 4);
  // The rule: the best-separated clustering over the candidate quantiles.
  const MeanShiftResult r = mean_shift(x, {});
  ASSERT_EQ(r.clusters(), 4);
  EXPECT_DOUBLE_EQ(adjusted_rand_index(r.labels, truth), 1.0);  // each blob one cluster
  EXPECT_GT(r.silhouette, 0.8);
  EXPECT_LT(r.quantile, 0.3);
  ASSERT_EQ(r.candidates.size(), 5u);  // every default quantile tried, in order
  for (const auto& c : r.candidates) EXPECT_LE(c.silhouette, r.silhouette);
  // Deterministic to the bit.
  EXPECT_EQ(mean_shift(x, {}).labels, r.labels);
  EXPECT_EQ(mean_shift(x, {}).bandwidth, r.bandwidth);
}

TEST(HarMeanShift, BandwidthRuleDoesNotSplitOneBlob) {
  // One Gaussian blob: every split is poorly separated; the rule must not
  // invent clusters beyond what the small-cluster fold leaves (a split of a
  // single Gaussian has silhouette well below a real one's).
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::MatrixXd x(600, 2);
  for (int i = 0; i < 600; ++i) x.row(i) << g(rng), g(rng);
  const MeanShiftResult r = mean_shift(x, {});
  EXPECT_LE(r.clusters(), 2);
  EXPECT_LT(r.silhouette, 0.5);
}

TEST(HarClusterMetrics, PurityAriAndSilhouetteMatchHandComputations) {
  // Perfect agreement up to renaming: purity 1, ARI 1.
  EXPECT_DOUBLE_EQ(cluster_purity({0, 0, 1, 1}, {1, 1, 0, 0}), 1.0);
  EXPECT_DOUBLE_EQ(adjusted_rand_index({0, 0, 1, 1}, {1, 1, 0, 0}), 1.0);
  // scikit-learn: adjusted_rand_score([0,0,1,1], [0,0,1,2]) = 0.5714285714285715
  EXPECT_NEAR(adjusted_rand_index({0, 0, 1, 1}, {0, 0, 1, 2}), 4.0 / 7.0, 1e-12);
  // ... adjusted_rand_score([0,0,1,1], [0,1,0,1]) = -0.5
  EXPECT_NEAR(adjusted_rand_index({0, 0, 1, 1}, {0, 1, 0, 1}), -0.5, 1e-12);
  // One cluster against two classes of 3 and 1: purity 3/4, ARI 0.
  EXPECT_DOUBLE_EQ(cluster_purity({0, 0, 0, 0}, {0, 0, 0, 1}), 0.75);
  EXPECT_DOUBLE_EQ(adjusted_rand_index({0, 0, 0, 0}, {0, 0, 0, 1}), 0.0);
  // Points 0, 1 | 5, 6 on a line: a = 1 and b = 5.5, 4.5, 4.5, 5.5 ->
  // s = 1 - 1/b per point; sklearn's silhouette_score gives 0.7979797979797979.
  Eigen::MatrixXd line(4, 1);
  line << 0, 1, 5, 6;
  EXPECT_NEAR(silhouette(line, {0, 0, 1, 1}), (2 * (1 - 1 / 5.5) + 2 * (1 - 1 / 4.5)) / 4, 1e-12);
  EXPECT_THROW(silhouette(line, {0, 0, 0, 0}), ptnet::Error);
  EXPECT_THROW(adjusted_rand_index({0, 1}, {0}), ptnet::Error);
  EXPECT_THROW(cluster_purity({0, -1}, {0, 0}), ptnet::Error);
}

TEST(HarClusterMetrics, RobustStandardiseIgnoresOutliersAndClips) {
  // A column of 0..9 plus one 1000: the median and MAD follow the bulk, so
  // the bulk keeps its spread and the outlier is clipped at +3.
  Eigen::MatrixXd x(11, 2);
  for (int i = 0; i < 10; ++i) x.row(i) << i, 7;
  x.row(10) << 1000, 7;
  robust_standardise(x, 3);
  // median 5, MAD = median |x - 5| = 3 -> scale 1.4826 * 3.
  EXPECT_NEAR(x(0, 0), (0 - 5) / (1.4826 * 3), 1e-12);
  EXPECT_NEAR(x(9, 0), (9 - 5) / (1.4826 * 3), 1e-12);
  EXPECT_DOUBLE_EQ(x(10, 0), 3.0);
  for (int i = 0; i < 11; ++i) EXPECT_EQ(x(i, 1), 0.0);  // a constant column is 0
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
