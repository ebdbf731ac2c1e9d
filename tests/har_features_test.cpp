// Window features and standardise + PCA on data with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

using namespace ptnet::har;

namespace {
int index_of(const std::string& name) {
  const auto& n = feature_names();
  for (int i = 0; i < int(n.size()); ++i)
    if (n[i] == name) return i;
  ADD_FAILURE() << "no feature " << name;
  return 0;
}
}  // namespace

TEST(HarFeatures, ForceAreaAndCentreOfPressureSpeedOfAMovingBlock) {
  // A 4 x 3-cell block of 10 kPa moving one row (2 cm) per frame along the
  // mat: 12 cells in contact, force 12 x 10 kPa x 4 cm^2 = 48 N, centre of
  // pressure speed 0.02 m x 30 fps = 0.6 m/s, path 29 x 0.02 m.
  ptnet::MatSpec mat;
  const int frames = 30;
  std::vector<float> w(std::size_t(frames) * mat.cells(), 0.0f);
  for (int t = 0; t < frames; ++t)
    for (int r = 10 + t; r < 14 + t; ++r)
      for (int c = 12; c < 15; ++c) w[std::size_t(t) * mat.cells() + r * mat.cols + c] = 10.0f;
  const std::vector<double> f = window_feature_vector(w.data(), frames, mat, 30);
  ASSERT_EQ(f.size(), feature_names().size());
  EXPECT_NEAR(f[index_of("force_mean_n")], 48.0, 1e-9);
  EXPECT_NEAR(f[index_of("force_cv")], 0.0, 1e-12);
  EXPECT_NEAR(f[index_of("area_mean_cells")], 12.0, 1e-12);
  EXPECT_NEAR(f[index_of("cop_speed_mean_mps")], 0.6, 1e-9);
  EXPECT_NEAR(f[index_of("cop_path_m")], 29 * 0.02, 1e-9);
  EXPECT_NEAR(f[index_of("cop_straightness")], 1.0, 1e-9);
  EXPECT_NEAR(f[index_of("cop_sd_y_m")], 0.0, 1e-12);
  EXPECT_NEAR(f[index_of("airborne_fraction")], 0.0, 1e-12);
  EXPECT_NEAR(f[index_of("peak_max_kpa")], 10.0, 1e-12);
}

TEST(HarFeatures, OccupancyGridIgnoresWherePeopleStandOnTheMat) {
  ptnet::MatSpec mat;
  auto window_at = [&](int r0, int c0) {
    std::vector<float> w(std::size_t(30) * mat.cells(), 0.0f);
    for (int t = 0; t < 30; ++t)
      for (int r = r0; r < r0 + 12; ++r)
        for (int c = c0; c < c0 + 4; ++c) w[std::size_t(t) * mat.cells() + r * mat.cols + c] = 20;
    return w;
  };
  const auto a = window_feature_vector(window_at(10, 4).data(), 30, mat);
  const auto b = window_feature_vector(window_at(50, 18).data(), 30, mat);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-9) << feature_names()[i];
}

TEST(HarPca, TwoCorrelatedColumnsGiveTheDiagonalDirection) {
  // Standardised columns with correlation rho: eigenvalues 1 +- rho, first
  // eigenvector (1, 1) / sqrt(2), explained (1 + rho) / 2 for one component.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0, 1);
  const int n = 2000;
  Eigen::MatrixXd x(n, 2);
  for (int i = 0; i < n; ++i) {
    const double t = g(rng);
    x(i, 0) = 3 + t;
    x(i, 1) = -7 + 50 * (t + 0.5 * g(rng));
  }
  Eigen::MatrixXd c = x.rowwise() - x.colwise().mean();
  const double rho = c.col(0).dot(c.col(1)) / (c.col(0).norm() * c.col(1).norm());
  Pca p = Pca::fit(x, 1);
  EXPECT_NEAR(p.components(0, 0), 1 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(p.components(1, 0), 1 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(p.variance(0), 1 + rho, 1e-9);
  EXPECT_NEAR(p.explained, (1 + rho) / 2, 1e-9);
  // The mean maps to the origin; projections have the component's variance.
  Eigen::MatrixXd z = p.transform(x);
  EXPECT_NEAR(z.mean(), 0.0, 1e-9);
  EXPECT_NEAR((z.array().square().sum()) / (n - 1), 1 + rho, 1e-9);
  Eigen::MatrixXd mean_row = x.colwise().mean();
  EXPECT_NEAR(p.transform(mean_row)(0, 0), 0.0, 1e-9);
}

TEST(HarPca, ConstantColumnIsHarmlessAndBadInputIsAnError) {
  Eigen::MatrixXd x(4, 2);
  x << 1, 5, 2, 5, 3, 5, 4, 5;
  Pca p = Pca::fit(x, 2);
  EXPECT_TRUE(p.transform(x).allFinite());
  EXPECT_NEAR(p.variance(0), 1.0, 1e-12);
  EXPECT_NEAR(p.variance(1), 0.0, 1e-12);
  EXPECT_THROW(Pca::fit(x, 3), ptnet::Error);
  EXPECT_THROW(Pca::fit(x.topRows(1), 1), ptnet::Error);
  try {
    p.transform(Eigen::MatrixXd(2, 3));
    FAIL();
  } catch (const ptnet::Error& e) {
    EXPECT_STREQ(e.what(), "pca: expected 2 columns, found 3");
  }
}

TEST(HarFeatures, BodyScaledFeaturesAreDividedBySubjectMedians) {
  // Two subjects, the second twice as heavy: after scaling both read 1 at
  // their median; features that do not scale with the body are untouched.
  const int nf = int(feature_names().size());
  const int force = index_of("force_mean_n"), speed = index_of("cop_speed_mean_mps");
  Eigen::MatrixXd x = Eigen::MatrixXd::Ones(6, nf);
  const double f[6] = {600, 700, 800, 1200, 1400, 1600};
  for (int i = 0; i < 6; ++i) {
    x(i, force) = f[i];
    x(i, speed) = 0.5 + i;
  }
  normalise_per_subject(x, {"a", "a", "a", "b", "b", "b"});
  EXPECT_NEAR(x(1, force), 1.0, 1e-12);
  EXPECT_NEAR(x(4, force), 1.0, 1e-12);
  EXPECT_NEAR(x(0, force), 600.0 / 700.0, 1e-12);
  EXPECT_NEAR(x(3, force), 1200.0 / 1400.0, 1e-12);
  EXPECT_EQ(x(5, speed), 5.5);
  EXPECT_THROW(normalise_per_subject(x, {"a"}), ptnet::Error);
}
