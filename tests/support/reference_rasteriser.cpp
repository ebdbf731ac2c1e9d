// The plain depth and foundation of reference_rasteriser.hpp.
#include "support/reference_rasteriser.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace ptnet::test {
namespace {

// The sample grid of the options, on and off the mat.
struct Grid {
  explicit Grid(const SimOptions& o)
      : s(o.subsamples),
        rows(o.mat.rows * o.subsamples),
        cols(o.mat.cols * o.subsamples),
        pitch(o.mat.pitch_m),
        ds(o.mat.pitch_m / o.subsamples),
        half_l(0.5 * o.mat.rows * o.mat.pitch_m),
        half_w(0.5 * o.mat.cols * o.mat.pitch_m) {}
  int s, rows, cols;
  double pitch, ds, half_l, half_w;

  double x(int i) const { return half_l - (i + 0.5) * ds; }
  double y(int j) const { return half_w - (j + 0.5) * ds; }
  bool on_mat(int i, int j) const { return i >= 0 && i < rows && j >= 0 && j < cols; }
  // The sample rows whose centre X lies in [x0, x1] (a superset: callers test X).
  std::pair<int, int> rows_over(double x0, double x1) const {
    return {int(std::floor((half_l - x1) / ds - 0.5)) - 1,
            int(std::ceil((half_l - x0) / ds - 0.5)) + 1};
  }
  std::pair<int, int> cols_over(double y0, double y1) const {
    return {int(std::floor((half_w - y1) / ds - 0.5)) - 1,
            int(std::ceil((half_w - y0) / ds - 0.5)) + 1};
  }
};

// The lowest surface per sample position, on and off the mat.
class Depth {
 public:
  Depth(const Grid& grid, float reach) : grid_(grid), reach_(reach) {}

  void record(int i, int j, float z, int owner, float u) {
    if (!(z < reach_)) return;
    const auto key = std::make_pair(i, j);
    const auto it = lowest_.find(key);
    if (it == lowest_.end() || z < it->second.z) lowest_[key] = {i, j, z, owner, u};
  }
  std::vector<RefSample> samples() const {
    std::vector<RefSample> out;
    for (const auto& [key, s] : lowest_) out.push_back(s);
    return out;
  }

 private:
  const Grid& grid_;
  float reach_;
  std::map<std::pair<int, int>, RefSample> lowest_;
};

void sole_patch(const Grid& g, const SoleSurface& sole, const SolePatch& p, int owner, float reach,
                Depth& depth) {
  const Eigen::Vector3d& n = p.up;
  if (n.z() < 0.2) return;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, zmin = 1e300;
  for (double u : {p.u_begin, p.u_end})
    for (double v : {sole.v_min, sole.v_max}) {
      const Eigen::Vector3d c = p.origin + p.forward * ((u - p.u_origin) * sole.length_m) +
                                p.left * (p.medial_sign * v * sole.width_m);
      x0 = std::min(x0, c.x()), x1 = std::max(x1, c.x());
      y0 = std::min(y0, c.y()), y1 = std::max(y1, c.y());
      zmin = std::min(zmin, c.z());
    }
  if (zmin > reach) return;
  const auto [i0, i1] = g.rows_over(x0, x1);
  const auto [j0, j1] = g.cols_over(y0, y1);
  const double rows = sole.nu - 1, cols = sole.nv - 1;
  for (int i = i0; i <= i1; ++i) {
    if (g.x(i) < x0 || g.x(i) > x1) continue;
    for (int j = j0; j <= j1; ++j) {
      if (g.y(j) < y0 || g.y(j) > y1) continue;
      // The plane point under the sample's centre, and its sole coordinates.
      const double dx = g.x(i) - p.origin.x(), dy = g.y(j) - p.origin.y();
      const double zp = p.origin.z() - (n.x() * dx + n.y() * dy) / n.z();
      const Eigen::Vector3d d(dx, dy, zp - p.origin.z());
      const double fi = (p.u_origin + d.dot(p.forward) / sole.length_m) * rows;
      const double v = p.medial_sign * d.dot(p.left) / sole.width_m;
      const double fj = (v - sole.v_min) / (sole.v_max - sole.v_min) * cols;
      if (fi < p.u_begin * rows - 0.5 || fi >= p.u_end * rows + 0.5) continue;
      if (fj < -0.5 || fj >= cols + 0.5) continue;
      const int ti = int(std::floor(fi + 0.5)), tj = int(std::floor(fj + 0.5));
      const float h = sole.height_m[std::size_t(ti) * sole.nv + std::size_t(tj)];
      if (!(h < SoleSurface::kOutside)) continue;
      depth.record(i, j, float(zp) + h * float(1 / n.z()), owner, float(fi / rows));
    }
  }
}

void sphere(const Grid& g, const Eigen::Vector3d& c, double r, Depth& depth) {
  const auto [i0, i1] = g.rows_over(c.x() - r, c.x() + r);
  const auto [j0, j1] = g.cols_over(c.y() - r, c.y() + r);
  for (int i = i0; i <= i1; ++i)
    for (int j = j0; j <= j1; ++j) {
      const double dx = g.x(i) - c.x(), dy = g.y(j) - c.y();
      const double d2 = dx * dx + dy * dy;
      if (d2 < r * r) depth.record(i, j, float(c.z() - std::sqrt(r * r - d2)), 3, 0.0f);
    }
}

void capsule(const Grid& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra,
             double rb, float reach, Depth& depth) {
  const int n = 1 + int(std::ceil((b - a).norm() / (std::min(ra, rb) / 3)));
  for (int k = 0; k <= n; ++k) {
    const double t = double(k) / n;
    const Eigen::Vector3d c = a + t * (b - a);
    const double r = ra + t * (rb - ra);
    if (c.z() - r <= reach) sphere(g, c, r, depth);
  }
}

float lowest(const std::vector<RefSample>& samples) {
  float z = std::numeric_limits<float>::infinity();
  for (const RefSample& s : samples) z = std::min(z, s.z);
  return z;
}

}  // namespace

std::vector<RefSample> reference_depth(const Body& body, const PosedBody& posed,
                                       const SimOptions& options) {
  const Grid g(options);
  const float reach = float(options.compliance_m + options.max_sink_m);
  Depth depth(g, reach);
  for (const SolePatch& p : posed.left_foot) sole_patch(g, body.sole(), p, 1, reach, depth);
  for (const SolePatch& p : posed.right_foot) sole_patch(g, body.sole(), p, 2, reach, depth);
  const auto& segs = body.segments();
  for (int s = 0; s < kSegmentCount; ++s)
    if (segs[s].touches_ground)
      capsule(g, posed.a[s], posed.b[s], segs[s].radius_a_m, segs[s].radius_b_m, reach, depth);
  return depth.samples();
}

double reference_sink_level(const std::vector<RefSample>& samples, double load_n,
                            const SimOptions& options) {
  const Grid g(options);
  const float zlo = lowest(samples), ztop = zlo + float(options.max_sink_m);
  const double target =
      load_n / (options.stiffness_kpa_per_mm * 1e6 * g.ds * g.ds);  // sum of (s - z), m
  std::vector<double> z;
  for (const RefSample& s : samples)
    if (s.z < ztop) z.push_back(s.z);
  std::sort(z.begin(), z.end());
  // Between the k-th and (k+1)-th lowest heights the sum is (k + 1) s - (their sum).
  double sum = 0;
  for (std::size_t k = 0; k < z.size(); ++k) {
    sum += z[k];
    const double level = (target + sum) / double(k + 1);
    const double next = k + 1 < z.size() ? z[k + 1] : double(ztop);
    if (level <= next) return level;
  }
  return z.empty() ? double(zlo) : double(ztop);
}

ReferenceFrame reference_distribute(const std::vector<RefSample>& samples, double level,
                                    double load_n, const Eigen::Vector2d* target,
                                    const SimOptions& options) {
  const Grid g(options);
  const MatSpec& mat = options.mat;
  ReferenceFrame out;
  out.kpa.assign(std::size_t(mat.cells()), 0.0);
  // 1. Contact.
  const float zlo = lowest(samples);
  if (!(zlo < float(options.compliance_m)) || !(load_n > 0)) return out;

  // 2. Mean penetration per cell (on the mat) and per sample (off it), m.
  struct Part {
    Eigen::Vector2d at;
    double pen;
  };
  std::vector<double> cell(std::size_t(mat.cells()), 0.0);
  std::vector<Part> off;
  const double per_sample = 1.0 / (g.s * g.s);
  for (const RefSample& s : samples) {
    const double pen = std::max(0.0, level - s.z) * per_sample;
    if (g.on_mat(s.i, s.j))
      cell[std::size_t(s.i / g.s * mat.cols + s.j / g.s)] += pen;
    else if (pen > 0)
      off.push_back({Eigen::Vector2d(g.x(s.i), g.y(s.j)), pen});
  }
  std::vector<Part> parts = off;
  for (int r = 0; r < mat.rows; ++r)
    for (int c = 0; c < mat.cols; ++c)
      if (cell[std::size_t(r * mat.cols + c)] > 0)
        parts.push_back(
            {Eigen::Vector2d(g.half_l - (r + 0.5) * g.pitch, g.half_w - (c + 0.5) * g.pitch),
             cell[std::size_t(r * mat.cols + c)]});
  double m0 = 0;
  Eigen::Vector2d centroid(0, 0);
  for (const Part& p : parts) m0 += p.pen, centroid += p.pen * p.at;
  if (!(m0 > 0)) return out;
  centroid /= m0;

  // 3. Tilt towards the target.
  Eigen::Matrix2d cov = Eigen::Matrix2d::Identity() * (g.pitch * g.pitch / 12);
  for (const Part& p : parts) cov += p.pen / m0 * (p.at - centroid) * (p.at - centroid).transpose();
  const Eigen::Matrix2d inv = cov.inverse();
  if (target) {
    Eigen::Vector2d shift = *target - centroid;
    const double maha = std::sqrt(shift.dot(inv * shift));
    if (maha > 0.6) shift *= 0.6 / maha;
    out.tilt = inv * shift;
  }
  auto weight = [&](const Eigen::Vector2d& at) {
    return std::max(0.0, 1.0 + out.tilt.dot(at - centroid));
  };
  for (const Part& p : parts) {
    out.max_penetration_m = std::max(out.max_penetration_m, p.pen);
    out.max_weight = std::max(out.max_weight, weight(p.at));
    const Eigen::Vector2d d = p.at - centroid;
    out.max_mahalanobis = std::max(out.max_mahalanobis, std::sqrt(d.dot(inv * d)));
  }

  // 4. Load scaling.
  double total = 0;
  for (const Part& p : parts) total += p.pen * weight(p.at);
  if (!(total > 0)) return out;
  out.unweighted_ratio = m0 / total;
  out.scale = load_n / (total * mat.cell_area_m2()) / 1000.0;
  for (int r = 0; r < mat.rows; ++r)
    for (int c = 0; c < mat.cols; ++c) {
      const std::size_t k = std::size_t(r * mat.cols + c);
      const Eigen::Vector2d at(g.half_l - (r + 0.5) * g.pitch, g.half_w - (c + 0.5) * g.pitch);
      if (cell[k] > 0) out.kpa[k] = cell[k] * weight(at) * out.scale;
    }

  // 5. Who carries what.
  FrameTrace& t = out.trace;
  t.load_n = load_n;
  t.sink_m = level - zlo;
  double cop[2] = {0, 0};
  for (const RefSample& s : samples) {
    const Eigen::Vector2d at = g.on_mat(s.i, s.j)
                                   ? Eigen::Vector2d(g.half_l - (s.i / g.s + 0.5) * g.pitch,
                                                     g.half_w - (s.j / g.s + 0.5) * g.pitch)
                                   : Eigen::Vector2d(g.x(s.i), g.y(s.j));
    const double pen = level - s.z, w = weight(at);
    if (!(pen > 0) || !(w > 0)) continue;
    const double f = pen * out.scale * 1000.0 * g.ds * g.ds * w;
    if (s.owner == 3) {
      t.other_n += f;
      continue;
    }
    FootLoad& foot = t.foot[std::size_t(s.owner - 1)];
    foot.force_n += f;
    foot.area_m2 += g.ds * g.ds;
    cop[s.owner - 1] += f * s.u;
    if (s.u < 0.3f) foot.heel_n += f;
    if (s.u >= 0.6f) foot.forefoot_n += f;
  }
  for (int k = 0; k < 2; ++k)
    if (t.foot[std::size_t(k)].force_n > 0)
      t.foot[std::size_t(k)].cop_u = cop[k] / t.foot[std::size_t(k)].force_n;
  return out;
}

}  // namespace ptnet::test
