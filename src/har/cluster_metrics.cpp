// Clustering agreement and quality (ptnet/har.hpp): purity and adjusted Rand
// index of a clustering against reference labels, mean silhouette.
//
// Dimension legend: N points, K dimensions, C clusters, R reference classes.
#include <algorithm>
#include <cmath>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {
namespace {

// [C, R] co-occurrence counts of two labelings of the same N points.
Eigen::MatrixXd contingency(const std::vector<int>& a, const std::vector<int>& b, const char* what) {
  if (a.size() != b.size())
    throw Error(std::string(what) + ": expected labelings of equal length, found " + std::to_string(a.size()) +
                " and " + std::to_string(b.size()));
  if (a.empty()) throw Error(std::string(what) + ": expected at least one point, found none");
  for (const auto* v : {&a, &b})
    for (int x : *v)
      if (x < 0) throw Error(std::string(what) + ": expected labels >= 0, found " + std::to_string(x));
  const int ca = *std::max_element(a.begin(), a.end()) + 1, cb = *std::max_element(b.begin(), b.end()) + 1;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(ca, cb);
  for (std::size_t i = 0; i < a.size(); ++i) m(a[i], b[i]) += 1;
  return m;
}

double pairs(double n) { return n * (n - 1) / 2; }

}  // namespace

double cluster_purity(const std::vector<int>& clusters, const std::vector<int>& truth) {
  const Eigen::MatrixXd m = contingency(clusters, truth, "purity");
  return m.rowwise().maxCoeff().sum() / double(clusters.size());
}

double adjusted_rand_index(const std::vector<int>& a, const std::vector<int>& b) {
  const Eigen::MatrixXd m = contingency(a, b, "adjusted Rand index");
  double index = 0, rows = 0, cols = 0;
  for (int i = 0; i < m.rows(); ++i) rows += pairs(m.row(i).sum());
  for (int j = 0; j < m.cols(); ++j) cols += pairs(m.col(j).sum());
  for (int i = 0; i < m.rows(); ++i)
    for (int j = 0; j < m.cols(); ++j) index += pairs(m(i, j));
  const double total = pairs(double(a.size()));
  const double expected = total > 0 ? rows * cols / total : 0;
  const double maximum = (rows + cols) / 2;
  if (maximum - expected == 0) return 1.0;  // both labelings trivial (scikit-learn's convention)
  return (index - expected) / (maximum - expected);
}

double silhouette(const Eigen::MatrixXd& x, const std::vector<int>& labels) {
  const int n = int(x.rows());
  if (int(labels.size()) != n)
    throw Error("silhouette: expected " + std::to_string(n) + " labels, found " + std::to_string(labels.size()));
  if (n == 0) throw Error("silhouette: expected at least one point, found none");
  const int c = *std::max_element(labels.begin(), labels.end()) + 1;
  std::vector<int> size(c, 0);
  for (int l : labels) {
    if (l < 0) throw Error("silhouette: expected labels >= 0, found " + std::to_string(l));
    ++size[l];
  }
  if (std::count_if(size.begin(), size.end(), [](int s) { return s > 0; }) < 2)
    throw Error("silhouette: expected at least 2 clusters, found 1");
  double total = 0;
  std::vector<double> sum(c);
  for (int i = 0; i < n; ++i) {
    std::fill(sum.begin(), sum.end(), 0.0);
    for (int j = 0; j < n; ++j)
      if (j != i) sum[labels[j]] += (x.row(i) - x.row(j)).norm();
    const int own = labels[i];
    if (size[own] < 2) continue;  // a singleton scores 0 (scikit-learn's convention)
    const double a = sum[own] / (size[own] - 1);
    double b = HUGE_VAL;
    for (int k = 0; k < c; ++k)
      if (k != own && size[k] > 0) b = std::min(b, sum[k] / size[k]);
    total += (b - a) / std::max(a, b);
  }
  return total / n;
}

}  // namespace ptnet::har
