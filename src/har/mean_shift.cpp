// Mean-shift clustering and its bandwidth rule (ptnet/har.hpp).
//
// Dimension legend: N points, K dimensions, S seeds, C clusters.
// Entirely deterministic: seeds come from an ordered bin map, ties are
// broken by index, there is no random number anywhere.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

double squared_distance(const double* a, const double* b, int k) {
  double s = 0;
  for (int j = 0; j < k; ++j) {
    const double d = a[j] - b[j];
    s += d * d;
  }
  return s;
}

// Climbs one seed to its mode. Returns false when the seed has no neighbour.
// `mode` [K] in/out; `support` = points within the bandwidth of the mode.
bool climb(const RowMajor& x, const MeanShiftOptions& o, double h, std::vector<double>& mode,
           int& support) {
  const int n = int(x.rows()), k = int(x.cols());
  const double h2 = h * h;
  const double reach2 = o.kernel == Kernel::flat ? h2 : 9.0 * h2;  // gaussian: 3 bandwidths
  const double stop2 = (o.tolerance * h) * (o.tolerance * h);
  std::vector<double> next(k);
  for (int it = 0; it < std::max(1, o.max_iterations); ++it) {
    std::fill(next.begin(), next.end(), 0.0);
    double weight = 0;
    int count = 0;
    for (int i = 0; i < n; ++i) {
      const double* p = x.data() + std::size_t(i) * k;
      const double d2 = squared_distance(p, mode.data(), k);
      if (d2 > reach2) continue;
      const double w = o.kernel == Kernel::flat ? 1.0 : std::exp(-0.5 * d2 / h2);
      for (int j = 0; j < k; ++j) next[j] += w * p[j];
      weight += w;
      if (d2 <= h2) ++count;
    }
    if (weight <= 0) return false;
    for (int j = 0; j < k; ++j) next[j] /= weight;
    const double moved2 = squared_distance(next.data(), mode.data(), k);
    mode.swap(next);
    support = count;
    if (moved2 <= stop2) break;
  }
  // Support at the final position.
  support = 0;
  for (int i = 0; i < n; ++i)
    if (squared_distance(x.data() + std::size_t(i) * k, mode.data(), k) <= h2) ++support;
  return true;
}

std::vector<int> nearest(const RowMajor& modes, const RowMajor& x, const std::vector<bool>* alive) {
  const int n = int(x.rows()), k = int(x.cols()), c = int(modes.rows());
  std::vector<int> out(n, 0);
  for (int i = 0; i < n; ++i) {
    double best = HUGE_VAL;
    for (int m = 0; m < c; ++m) {
      if (alive && !(*alive)[m]) continue;
      const double d2 = squared_distance(x.data() + std::size_t(i) * k,
                                         modes.data() + std::size_t(m) * k, k);
      if (d2 < best) {
        best = d2;
        out[i] = m;
      }
    }
  }
  return out;
}

}  // namespace

double estimate_bandwidth(const Eigen::MatrixXd& x, double quantile, int max_points) {
  const int n = int(x.rows());
  if (n < 2) throw Error("mean shift: need at least 2 points to estimate a bandwidth, found " +
                         std::to_string(n));
  if (!(quantile > 0 && quantile <= 1))
    throw Error("mean shift: quantile must be in (0, 1], found " + std::to_string(quantile));
  if (max_points < 2) max_points = 2;
  const int step = (n + max_points - 1) / max_points;
  std::vector<int> rows;
  for (int i = 0; i < n; i += step) rows.push_back(i);
  const int m = int(rows.size());
  if (m < 2) rows.push_back(n - 1);
  const int mm = int(rows.size());
  const int kth = std::max(1, int(std::lround(quantile * (mm - 1))));  // 1-based among others
  RowMajor sub(mm, x.cols());
  for (int i = 0; i < mm; ++i) sub.row(i) = x.row(rows[i]);
  const int k = int(x.cols());
  double total = 0;
  std::vector<double> d(mm - 1);
  for (int i = 0; i < mm; ++i) {
    int o = 0;
    for (int j = 0; j < mm; ++j)
      if (j != i) d[o++] = squared_distance(sub.data() + std::size_t(i) * k,
                                            sub.data() + std::size_t(j) * k, k);
    std::nth_element(d.begin(), d.begin() + (kth - 1), d.end());
    total += std::sqrt(d[kth - 1]);
  }
  return std::max(1e-12, total / mm);
}

std::vector<int> assign_nearest(const Eigen::MatrixXd& modes, const Eigen::MatrixXd& x) {
  if (modes.rows() == 0) throw Error("mean shift: no modes to assign to");
  if (modes.cols() != x.cols())
    throw Error("mean shift: modes have " + std::to_string(modes.cols()) +
                " dimensions, points " + std::to_string(x.cols()));
  const RowMajor m = modes, p = x;
  return nearest(m, p, nullptr);
}

namespace {

// ---- the phases of mean_shift(), in order

// Seeds: centres of occupied bandwidth-sized bins (ordered map: fixed
// order), or every point when binning does not reduce them.
std::vector<std::vector<double>> seeds_of(const RowMajor& x, const MeanShiftOptions& o, double h) {
  const int n = int(x.rows()), k = int(x.cols());
  std::vector<std::vector<double>> seeds;
  if (o.bin_seeding) {
    std::map<std::vector<long long>, int> bins;
    std::vector<long long> key(k);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < k; ++j) key[j] = std::llround(x(i, j) / h);
      ++bins[key];
    }
    if (int(bins.size()) < n) {
      for (const auto& [b, count] : bins) {
        if (count < o.min_bin_count) continue;
        std::vector<double> s(k);
        for (int j = 0; j < k; ++j) s[j] = double(b[j]) * h;
        seeds.push_back(std::move(s));
      }
    }
  }
  if (seeds.empty())
    for (int i = 0; i < n; ++i) seeds.emplace_back(x.data() + std::size_t(i) * k, x.data() + std::size_t(i + 1) * k);
  return seeds;
}

struct Mode {
  std::vector<double> at;
  int support;
  int order;
};

// Every seed climbed to its mode, best supported first; `seed_count` grows by n
// when no bin centre reached one (high K) and the points seed instead.
std::vector<Mode> climb_modes(const RowMajor& x, const MeanShiftOptions& o, double h,
                              const std::vector<std::vector<double>>& seeds, int& seed_count) {
  const int n = int(x.rows()), k = int(x.cols());
  std::vector<Mode> modes;
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    std::vector<double> m = seeds[s];
    int support = 0;
    if (climb(x, o, h, m, support)) modes.push_back({std::move(m), support, int(s)});
  }
  if (modes.empty()) {  // bin centres too far from every point (high K): seed with the points
    for (int i = 0; i < n; ++i) {
      std::vector<double> m(x.data() + std::size_t(i) * k, x.data() + std::size_t(i + 1) * k);
      int support = 0;
      if (climb(x, o, h, m, support)) modes.push_back({std::move(m), support, i});
    }
    seed_count += n;
  }
  std::stable_sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) { return a.support > b.support; });
  return modes;
}

// Merge: a mode within merge_distance x h of a better-supported one is
// dropped. [C, K].
RowMajor merge_modes(const std::vector<Mode>& modes, const MeanShiftOptions& o, double h, int k) {
  const double merge2 = (o.merge_distance * h) * (o.merge_distance * h);
  std::vector<std::vector<double>> kept;
  for (const Mode& m : modes) {
    bool near = false;
    for (const auto& q : kept)
      if (squared_distance(m.at.data(), q.data(), k) < merge2) {
        near = true;
        break;
      }
    if (!near) kept.push_back(m.at);
  }
  RowMajor centres(int(kept.size()), k);
  for (int c = 0; c < int(kept.size()); ++c)
    for (int j = 0; j < k; ++j) centres(c, j) = kept[c][j];
  return centres;
}

// Assign, then fold clusters smaller than the minimum fraction, smallest
// first: their points go to the nearest remaining mode. Labels [N] into
// `centres`; `alive` [C] marks the modes kept.
std::vector<int> assign_and_fold(const RowMajor& centres, const RowMajor& x, const MeanShiftOptions& o,
                                 std::vector<bool>& alive) {
  const int n = int(x.rows()), c0 = int(centres.rows());
  alive.assign(c0, true);
  std::vector<int> labels = nearest(centres, x, &alive);
  const long long min_size = (long long)std::ceil(o.min_cluster_fraction * n);
  for (;;) {
    std::vector<long long> size(c0, 0);
    for (int l : labels) ++size[l];
    int worst = -1, live = 0;
    for (int c = 0; c < c0; ++c) {
      if (!alive[c]) continue;
      ++live;
      if (size[c] < min_size && (worst < 0 || size[c] <= size[worst])) worst = c;
    }
    if (worst < 0 || live <= 1) break;
    alive[worst] = false;
    labels = nearest(centres, x, &alive);
  }
  return labels;
}

// Renumber by size (largest first; ties by mode order) into r.modes,
// r.sizes and r.labels.
void renumber(const RowMajor& centres, const std::vector<int>& labels, const std::vector<bool>& alive,
              MeanShiftResult& r) {
  const int n = int(labels.size()), c0 = int(centres.rows()), k = int(centres.cols());
  std::vector<int> size(c0, 0);
  for (int l : labels) ++size[l];
  std::vector<int> order;
  for (int c = 0; c < c0; ++c)
    if (alive[c] && size[c] > 0) order.push_back(c);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return size[a] > size[b]; });
  std::vector<int> remap(c0, -1);
  r.modes.resize(int(order.size()), k);
  for (int i = 0; i < int(order.size()); ++i) {
    remap[order[i]] = i;
    r.modes.row(i) = centres.row(order[i]);
    r.sizes.push_back(size[order[i]]);
  }
  r.labels.resize(n);
  for (int i = 0; i < n; ++i) r.labels[i] = remap[labels[i]];
}

}  // namespace

namespace {

// One clustering at bandwidth h (seeds, climb, merge, fold, renumber).
MeanShiftResult mean_shift_at(const RowMajor& x, const MeanShiftOptions& o, double h) {
  MeanShiftResult r;
  r.bandwidth = h;
  const auto seeds = seeds_of(x, o, h);
  r.seeds = int(seeds.size());
  const std::vector<Mode> modes = climb_modes(x, o, h, seeds, r.seeds);
  const RowMajor centres = merge_modes(modes, o, h, int(x.cols()));
  std::vector<bool> alive;
  const std::vector<int> labels = assign_and_fold(centres, x, o, alive);
  renumber(centres, labels, alive, r);
  return r;
}

// Silhouette on every ceil(N / max_points)-th point (scikit-learn's
// sample_size, without its randomness); -1 when fewer than 2 clusters show.
double sampled_silhouette(const Eigen::MatrixXd& x, const std::vector<int>& labels, int max_points) {
  const int n = int(x.rows());
  const int step = (n + std::max(2, max_points) - 1) / std::max(2, max_points);
  std::vector<int> rows;
  for (int i = 0; i < n; i += step) rows.push_back(i);
  Eigen::MatrixXd sub(int(rows.size()), x.cols());
  std::vector<int> sub_labels;
  for (int i = 0; i < int(rows.size()); ++i) {
    sub.row(i) = x.row(rows[i]);
    sub_labels.push_back(labels[rows[i]]);
  }
  const std::vector<int> sorted = [&] {
    std::vector<int> v = sub_labels;
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
  }();
  if (sorted.size() < 2) return -1;
  return silhouette(sub, sub_labels);
}

}  // namespace

MeanShiftResult mean_shift(const Eigen::MatrixXd& input, const MeanShiftOptions& o) {
  const int n = int(input.rows()), k = int(input.cols());
  if (n < 1 || k < 1) throw Error("mean shift: no points to cluster");
  if (!input.allFinite()) throw Error("mean shift: points contain NaN or infinity");
  const RowMajor x = input;
  if (o.bandwidth > 0 || n < 2) {
    MeanShiftResult r = mean_shift_at(x, o, o.bandwidth > 0 ? o.bandwidth : 1.0);
    if (r.clusters() > 1) r.silhouette = sampled_silhouette(input, r.labels, o.silhouette_points);
    return r;
  }
  if (o.quantiles.empty()) throw Error("mean shift: expected a bandwidth or at least one quantile, found neither");
  // The bandwidth rule: one clustering per candidate quantile, the best
  // separated (highest silhouette) wins; a tie goes to fewer clusters.
  MeanShiftResult best;
  bool have = false;
  std::vector<BandwidthCandidate> tried;
  for (double q : o.quantiles) {
    MeanShiftResult r = mean_shift_at(x, o, estimate_bandwidth(input, q));
    r.quantile = q;
    r.silhouette = r.clusters() > 1 ? sampled_silhouette(input, r.labels, o.silhouette_points) : -1;
    tried.push_back({q, r.bandwidth, r.clusters(), r.silhouette});
    if (!have || r.silhouette > best.silhouette ||
        (r.silhouette == best.silhouette && r.clusters() < best.clusters())) {
      best = std::move(r);
      have = true;
    }
  }
  best.candidates = std::move(tried);
  return best;
}

}  // namespace ptnet::har
