// Hand-made window features and standardise + PCA (ptnet/har.hpp).
//
// Dimension legend: T frames per window, H x W mat cells, F features, K
// components. Mat geometry as in ptnet/pressure.hpp: cell (r, c) centre at
// x = L/2 - (r + 0.5) p along the mat, y = W/2 - (c + 0.5) p across.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {
namespace {

constexpr double kAirborneFraction = 0.05;  // a frame below 5 % of the window's mean force is airborne

struct Stats {
  double mean = 0, sd = 0, min = 0, max = 0;
};

Stats stats(const std::vector<double>& v) {
  Stats s;
  if (v.empty()) return s;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  for (double x : v) s.mean += x;
  s.mean /= double(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(s.sd / double(v.size()));
  return s;
}

}  // namespace

const std::vector<std::string>& feature_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n = {
        "force_mean_n",        "force_cv",           "force_min_rel",     "force_max_rel",
        "force_change_rel_hz", "force_crossings_hz", "airborne_fraction", "area_mean_cells",
        "area_sd_cells",       "area_min_cells",     "area_max_cells",    "cop_path_m",
        "cop_speed_mean_mps",  "cop_speed_max_mps",  "cop_sd_x_m",        "cop_sd_y_m",
        "cop_range_x_m",       "cop_range_y_m",      "cop_net_m",         "cop_straightness",
        "spread_x_m",          "spread_y_m",         "mean_map_spread_x_m", "mean_map_spread_y_m",
        "peak_mean_kpa",       "peak_max_kpa",       "map_change_rel"};
    for (int i = 0; i < kCentredGridRows; ++i)
      for (int j = 0; j < kCentredGridCols; ++j)
        n.push_back("occupancy_" + std::to_string(i) + "_" + std::to_string(j));
    return n;
  }();
  return names;
}

namespace {

// Per-frame quantities of a window [T, H, W] kPa, and the window-averaged map.
struct FrameSeries {
  std::vector<double> force, area, peak;          // [T] N, cells in contact, kPa
  std::vector<double> cop_x, cop_y;               // [T] centre of pressure (m), 0 when unloaded
  std::vector<double> cop_r, cop_c;               // [T] the same in cell units
  std::vector<double> spread_x, spread_y;         // [T] load spread about it (m)
  std::vector<double> mean_map;                   // [H, W] kPa averaged over the frames
  double change = 0, change_norm = 0;             // sum |frame t - frame t-1|, sum of all load
  std::vector<int> loaded;                        // frames with load (centre of pressure defined)
  double force_mean = 0;
};

FrameSeries frame_series(const float* window, int frames, const MatSpec& mat) {
  const int rows = mat.rows, cols = mat.cols, cells = mat.cells();
  const double to_newton = 1000.0 * mat.cell_area_m2();  // kPa on one cell -> N
  FrameSeries s;
  for (auto* v : {&s.force, &s.area, &s.peak, &s.cop_x, &s.cop_y, &s.cop_r, &s.cop_c, &s.spread_x, &s.spread_y})
    v->assign(frames, 0.0);
  s.mean_map.assign(cells, 0.0);
  for (int t = 0; t < frames; ++t) {
    const float* f = window + std::size_t(t) * cells;
    double sum = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sr = 0, sc = 0, pk = 0;
    int contact = 0;
    for (int r = 0; r < rows; ++r) {
      const double x = mat.cell_x(r);
      for (int c = 0; c < cols; ++c) {
        const double v = std::max(0.0f, f[r * cols + c]);
        if (v <= 0) continue;
        const double y = mat.cell_y(c);
        sum += v;
        sx += v * x;
        sy += v * y;
        sxx += v * x * x;
        syy += v * y * y;
        sr += v * r;
        sc += v * c;
        pk = std::max(pk, v);
        if (v > kContactKpa) ++contact;
        s.mean_map[r * cols + c] += v / frames;
      }
    }
    s.force[t] = sum * to_newton;
    s.area[t] = contact;
    s.peak[t] = pk;
    if (sum > 0) {
      s.cop_x[t] = sx / sum;
      s.cop_y[t] = sy / sum;
      s.cop_r[t] = sr / sum;
      s.cop_c[t] = sc / sum;
      s.spread_x[t] = std::sqrt(std::max(0.0, sxx / sum - s.cop_x[t] * s.cop_x[t]));
      s.spread_y[t] = std::sqrt(std::max(0.0, syy / sum - s.cop_y[t] * s.cop_y[t]));
    }
    if (t > 0) {
      const float* g = f - cells;
      for (int i = 0; i < cells; ++i) s.change += std::fabs(double(f[i]) - double(g[i]));
    }
    s.change_norm += sum;
  }
  s.force_mean = stats(s.force).mean;
  for (int t = 0; t < frames; ++t)
    if (s.force[t] > 0 && !(s.force[t] < kAirborneFraction * s.force_mean)) s.loaded.push_back(t);
  return s;
}

// Mean of a per-frame series [T] over the loaded frames; `none` without any.
double loaded_mean(const FrameSeries& s, const std::vector<double>& series, double none) {
  if (s.loaded.empty()) return none;
  double sum = 0;
  for (int t : s.loaded) sum += series[t];
  return sum / double(s.loaded.size());
}

// Force (mean, variation, changes, airborne frames) and contact area.
void add_force_features(const FrameSeries& s, int frames, double seconds, std::vector<double>& out) {
  const Stats fs = stats(s.force);
  const double fm = fs.mean > 1e-9 ? fs.mean : 1.0;
  double force_change = 0;
  int crossings = 0;
  for (int t = 1; t < frames; ++t) {
    force_change += std::fabs(s.force[t] - s.force[t - 1]);
    if ((s.force[t] - fs.mean) * (s.force[t - 1] - fs.mean) < 0) ++crossings;
  }
  int airborne = 0;
  for (int t = 0; t < frames; ++t)
    if (s.force[t] < kAirborneFraction * fs.mean || s.force[t] <= 0) ++airborne;
  out.push_back(fs.mean);
  out.push_back(fs.sd / fm);
  out.push_back(fs.min / fm);
  out.push_back(fs.max / fm);
  out.push_back(force_change / fm / seconds);
  out.push_back(crossings / seconds);
  out.push_back(double(airborne) / frames);
  const Stats as = stats(s.area);
  out.push_back(as.mean);
  out.push_back(as.sd);
  out.push_back(as.min);
  out.push_back(as.max);
}

// Centre-of-pressure path over the loaded frames.
void add_cop_features(const FrameSeries& s, double seconds, double fps, std::vector<double>& out) {
  double path = 0, speed_max = 0;
  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < s.loaded.size(); ++i) {
    const int t = s.loaded[i];
    lx.push_back(s.cop_x[t]);
    ly.push_back(s.cop_y[t]);
    if (i > 0) {
      const int u = s.loaded[i - 1];
      const double d = std::hypot(s.cop_x[t] - s.cop_x[u], s.cop_y[t] - s.cop_y[u]);
      path += d;
      speed_max = std::max(speed_max, d * fps / (t - u));
    }
  }
  const Stats xs = stats(lx), ys = stats(ly);
  double net = 0;
  if (s.loaded.size() > 1) net = std::hypot(lx.back() - lx.front(), ly.back() - ly.front());
  out.push_back(path);
  out.push_back(path / seconds);
  out.push_back(speed_max);
  out.push_back(xs.sd);
  out.push_back(ys.sd);
  out.push_back(xs.max - xs.min);
  out.push_back(ys.max - ys.min);
  out.push_back(net);
  out.push_back(path > 1e-9 ? net / path : 0.0);
}

// Spread of the load within a frame and of the window-averaged map; peak
// pressure; how much the map changes.
void add_spread_features(const FrameSeries& s, const MatSpec& mat, std::vector<double>& out) {
  out.push_back(loaded_mean(s, s.spread_x, 0.0));
  out.push_back(loaded_mean(s, s.spread_y, 0.0));
  double sum = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
  for (int r = 0; r < mat.rows; ++r)
    for (int c = 0; c < mat.cols; ++c) {
      const double v = s.mean_map[r * mat.cols + c];
      if (v <= 0) continue;
      const double x = mat.cell_x(r), y = mat.cell_y(c);
      sum += v;
      sx += v * x;
      sy += v * y;
      sxx += v * x * x;
      syy += v * y * y;
    }
  const double mx = sum > 0 ? sx / sum : 0, my = sum > 0 ? sy / sum : 0;
  out.push_back(sum > 0 ? std::sqrt(std::max(0.0, sxx / sum - mx * mx)) : 0.0);
  out.push_back(sum > 0 ? std::sqrt(std::max(0.0, syy / sum - my * my)) : 0.0);
  const Stats ps = stats(s.peak);
  out.push_back(ps.mean);
  out.push_back(ps.max);
  out.push_back(s.change_norm > 1e-9 ? s.change / s.change_norm : 0.0);
}

// Contact occupancy in a grid of blocks centred on the window's mean centre
// of pressure (in cell units): fraction of block cells in contact, averaged
// over the frames.
void add_occupancy_features(const float* window, int frames, const MatSpec& mat, const FrameSeries& s,
                            std::vector<double>& out) {
  const int rows = mat.rows, cols = mat.cols, cells = mat.cells();
  const double mr = loaded_mean(s, s.cop_r, rows / 2.0), mc = loaded_mean(s, s.cop_c, cols / 2.0);
  std::vector<double> grid(kCentredGridRows * kCentredGridCols, 0.0);
  const double r0 = mr - kCentredGridRows * kCentredBlockRows / 2.0;
  const double c0 = mc - kCentredGridCols * kCentredBlockCols / 2.0;
  for (int t = 0; t < frames; ++t) {
    const float* f = window + std::size_t(t) * cells;
    for (int r = 0; r < rows; ++r) {
      const int br = int(std::floor((r + 0.5 - r0) / kCentredBlockRows));
      if (br < 0 || br >= kCentredGridRows) continue;
      for (int c = 0; c < cols; ++c) {
        if (!(f[r * cols + c] > kContactKpa)) continue;
        const int bc = int(std::floor((c + 0.5 - c0) / kCentredBlockCols));
        if (bc < 0 || bc >= kCentredGridCols) continue;
        grid[br * kCentredGridCols + bc] += 1.0;
      }
    }
  }
  for (double g : grid) out.push_back(g / (frames * kCentredBlockRows * kCentredBlockCols));
}

}  // namespace

// window [T, H, W] kPa -> [F] (units in feature_names()).
std::vector<double> window_feature_vector(const float* window, int frames, const MatSpec& mat, double fps) {
  const FrameSeries s = frame_series(window, frames, mat);
  const double seconds = frames > 1 ? (frames - 1) / fps : 1.0;
  std::vector<double> out;
  out.reserve(feature_names().size());
  add_force_features(s, frames, seconds, out);
  add_cop_features(s, seconds, fps, out);
  add_spread_features(s, mat, out);
  add_occupancy_features(window, frames, mat, s, out);
  return out;
}

// [N, T, H, W] -> [N, F].
Eigen::MatrixXd window_features(const WindowBatch& windows, double fps) {
  const int n = windows.count();
  const int f = int(feature_names().size());
  Eigen::MatrixXd x(n, f);
  for (int i = 0; i < n; ++i) {
    const std::vector<double> v = window_feature_vector(windows.window(i), windows.frames,
                                                        windows.mat, fps);
    for (int j = 0; j < f; ++j) x(i, j) = v[j];
  }
  return x;
}

void robust_standardise(Eigen::MatrixXd& features, double clip) {
  if (!(clip > 0)) throw Error("robust standardise: expected clip > 0, found " + std::to_string(clip));
  const int n = int(features.rows());
  if (n == 0) return;
  std::vector<double> v(n);
  auto median = [&] {
    std::nth_element(v.begin(), v.begin() + n / 2, v.end());
    return v[n / 2];
  };
  for (int j = 0; j < features.cols(); ++j) {
    for (int i = 0; i < n; ++i) v[i] = features(i, j);
    const double centre = median();
    for (int i = 0; i < n; ++i) v[i] = std::fabs(features(i, j) - centre);
    double scale = 1.4826 * median();  // MAD -> sd of a normal distribution
    if (!(scale > 1e-12)) {
      const double mean = features.col(j).mean();
      scale = std::sqrt((features.col(j).array() - mean).square().mean());
    }
    for (int i = 0; i < n; ++i)
      features(i, j) = scale > 1e-12 ? std::clamp((features(i, j) - centre) / scale, -clip, clip) : 0.0;
  }
}

Pca Pca::fit(const Eigen::MatrixXd& x, int k) {
  const int n = int(x.rows()), f = int(x.cols());
  if (n < 2) throw Error("pca: need at least 2 rows, found " + std::to_string(n));
  if (k < 1 || k > f)
    throw Error("pca: components must be in 1.." + std::to_string(f) + ", found " +
                std::to_string(k));
  Pca p;
  p.mean = x.colwise().mean();
  Eigen::MatrixXd centred = x.rowwise() - p.mean;
  p.scale = (centred.array().square().colwise().sum() / double(n - 1)).sqrt();
  for (int j = 0; j < f; ++j)
    if (!(p.scale(j) > 1e-12 * (1.0 + std::fabs(p.mean(j))))) p.scale(j) = 1.0;
  Eigen::MatrixXd z = centred.array().rowwise() / p.scale.array();
  Eigen::MatrixXd cov = (z.transpose() * z) / double(n - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
  if (eig.info() != Eigen::Success) throw Error("pca: eigen decomposition failed");
  p.components.resize(f, k);
  p.variance.resize(k);
  const double total = std::max(1e-300, eig.eigenvalues().sum());
  double kept = 0;
  for (int i = 0; i < k; ++i) {
    const int src = f - 1 - i;  // eigenvalues ascending
    Eigen::VectorXd v = eig.eigenvectors().col(src);
    Eigen::Index big = 0;
    v.cwiseAbs().maxCoeff(&big);
    if (v(big) < 0) v = -v;
    p.components.col(i) = v;
    p.variance(i) = std::max(0.0, eig.eigenvalues()(src));
    kept += p.variance(i);
  }
  p.explained = kept / total;
  return p;
}

Eigen::MatrixXd Pca::transform(const Eigen::MatrixXd& x) const {
  if (x.cols() != mean.size())
    throw Error("pca: expected " + std::to_string(mean.size()) + " columns, found " +
                std::to_string(x.cols()));
  Eigen::MatrixXd z = (x.rowwise() - mean).array().rowwise() / scale.array();
  return z * components;
}

}  // namespace ptnet::har
