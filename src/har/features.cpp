// Hand-made window features and standardise + PCA (ptnet/har.hpp).
//
// Dimension legend: T frames per window, H x W mat cells, F features, K
// components. Mat geometry as in ptnet/pressure.hpp: cell (r, c) centre at
// x = L/2 - (r + 0.5) p along the mat, y = W/2 - (c + 0.5) p across.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

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

// window [T, H, W] kPa -> [F] (units in feature_names()).
std::vector<double> window_feature_vector(const float* window, int frames, const MatSpec& mat,
                                          double fps) {
  const int rows = mat.rows, cols = mat.cols, cells = mat.cells();
  const double p = mat.pitch_m;
  const double half_l = rows * p / 2, half_w = cols * p / 2;
  const double to_newton = 1000.0 * mat.cell_area_m2();  // kPa on one cell -> N
  std::vector<double> force(frames), area(frames), peak(frames);
  std::vector<double> cop_x(frames, 0), cop_y(frames, 0), spread_x(frames, 0), spread_y(frames, 0);
  std::vector<double> cop_r(frames, 0), cop_c(frames, 0);
  std::vector<double> mean_map(cells, 0.0);
  double change = 0, change_norm = 0;
  for (int t = 0; t < frames; ++t) {
    const float* f = window + std::size_t(t) * cells;
    double sum = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sr = 0, sc = 0, pk = 0;
    int contact = 0;
    for (int r = 0; r < rows; ++r) {
      const double x = half_l - (r + 0.5) * p;
      for (int c = 0; c < cols; ++c) {
        const double v = std::max(0.0f, f[r * cols + c]);
        if (v <= 0) continue;
        const double y = half_w - (c + 0.5) * p;
        sum += v;
        sx += v * x;
        sy += v * y;
        sxx += v * x * x;
        syy += v * y * y;
        sr += v * r;
        sc += v * c;
        pk = std::max(pk, v);
        if (v > kContactKpa) ++contact;
        mean_map[r * cols + c] += v / frames;
      }
    }
    force[t] = sum * to_newton;
    area[t] = contact;
    peak[t] = pk;
    if (sum > 0) {
      cop_x[t] = sx / sum;
      cop_y[t] = sy / sum;
      cop_r[t] = sr / sum;
      cop_c[t] = sc / sum;
      spread_x[t] = std::sqrt(std::max(0.0, sxx / sum - cop_x[t] * cop_x[t]));
      spread_y[t] = std::sqrt(std::max(0.0, syy / sum - cop_y[t] * cop_y[t]));
    }
    if (t > 0) {
      const float* g = f - cells;
      for (int i = 0; i < cells; ++i) change += std::fabs(double(f[i]) - double(g[i]));
    }
    change_norm += sum;
  }

  std::vector<double> out;
  out.reserve(feature_names().size());
  const Stats fs = stats(force);
  const double fm = fs.mean > 1e-9 ? fs.mean : 1.0;
  double force_change = 0;
  int crossings = 0;
  for (int t = 1; t < frames; ++t) {
    force_change += std::fabs(force[t] - force[t - 1]);
    if ((force[t] - fs.mean) * (force[t - 1] - fs.mean) < 0) ++crossings;
  }
  const double seconds = frames > 1 ? (frames - 1) / fps : 1.0;
  int airborne = 0;
  std::vector<int> loaded;  // frames with load (centre of pressure defined)
  for (int t = 0; t < frames; ++t) {
    if (force[t] < kAirborneFraction * fs.mean || force[t] <= 0) ++airborne;
    if (force[t] > 0 && !(force[t] < kAirborneFraction * fs.mean)) loaded.push_back(t);
  }
  out.push_back(fs.mean);
  out.push_back(fs.sd / fm);
  out.push_back(fs.min / fm);
  out.push_back(fs.max / fm);
  out.push_back(force_change / fm / seconds);
  out.push_back(crossings / seconds);
  out.push_back(double(airborne) / frames);
  const Stats as = stats(area);
  out.push_back(as.mean);
  out.push_back(as.sd);
  out.push_back(as.min);
  out.push_back(as.max);

  // Centre-of-pressure path over the loaded frames.
  double path = 0, speed_max = 0;
  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    const int t = loaded[i];
    lx.push_back(cop_x[t]);
    ly.push_back(cop_y[t]);
    if (i > 0) {
      const int u = loaded[i - 1];
      const double d = std::hypot(cop_x[t] - cop_x[u], cop_y[t] - cop_y[u]);
      path += d;
      speed_max = std::max(speed_max, d * fps / (t - u));
    }
  }
  const Stats xs = stats(lx), ys = stats(ly);
  double net = 0;
  if (loaded.size() > 1)
    net = std::hypot(lx.back() - lx.front(), ly.back() - ly.front());
  out.push_back(path);
  out.push_back(path / seconds);
  out.push_back(speed_max);
  out.push_back(xs.sd);
  out.push_back(ys.sd);
  out.push_back(xs.max - xs.min);
  out.push_back(ys.max - ys.min);
  out.push_back(net);
  out.push_back(path > 1e-9 ? net / path : 0.0);

  // Spread of the load within a frame and of the window-averaged map.
  double spx = 0, spy = 0;
  for (int t : loaded) {
    spx += spread_x[t];
    spy += spread_y[t];
  }
  if (!loaded.empty()) {
    spx /= double(loaded.size());
    spy /= double(loaded.size());
  }
  out.push_back(spx);
  out.push_back(spy);
  {
    double s = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        const double v = mean_map[r * cols + c];
        if (v <= 0) continue;
        const double x = half_l - (r + 0.5) * p, y = half_w - (c + 0.5) * p;
        s += v;
        sx += v * x;
        sy += v * y;
        sxx += v * x * x;
        syy += v * y * y;
      }
    double mx = s > 0 ? sx / s : 0, my = s > 0 ? sy / s : 0;
    out.push_back(s > 0 ? std::sqrt(std::max(0.0, sxx / s - mx * mx)) : 0.0);
    out.push_back(s > 0 ? std::sqrt(std::max(0.0, syy / s - my * my)) : 0.0);
  }
  const Stats ps = stats(peak);
  out.push_back(ps.mean);
  out.push_back(ps.max);
  out.push_back(change_norm > 1e-9 ? change / change_norm : 0.0);

  // Contact occupancy in a grid of blocks centred on the window's mean
  // centre of pressure (in cell units): fraction of block cells in contact,
  // averaged over the frames.
  double mr = 0, mc = 0;
  for (int t : loaded) {
    mr += cop_r[t];
    mc += cop_c[t];
  }
  if (!loaded.empty()) {
    mr /= double(loaded.size());
    mc /= double(loaded.size());
  } else {
    mr = rows / 2.0;
    mc = cols / 2.0;
  }
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
