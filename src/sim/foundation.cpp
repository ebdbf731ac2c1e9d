// The elastic foundation (Foundation): a frame's depth map (rasterise.cpp)
// sunk into the mat until the body carries its load, in five steps, each a
// function below: the sink level, the penetration per cell, the tilt
// towards the zero-moment point, the scaling to the load, and who carries
// what (the trace). The model: ptnet/sim.hpp, step 5; the steps:
// sim_internal.hpp.
//
// The heights are binned for the sink level four samples at a time
// (bin_heights_sse2, beside its scalar twin bin_heights); the rest is
// scalar, in a fixed order (the same bytes on every CPU).
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "sim_internal.hpp"

namespace ptnet::detail {
namespace {

constexpr int kBins = 64;          // sink level: histogram bins over the maximum sink
constexpr double kMaxShift = 0.6;  // tilt: standard deviations; every contact cell keeps some load

// Heights below ztop, binned by (z - zlo) / w: a count and a sum per bin.
struct Histogram {
  float zlo, ztop, inv_w;
  int count[kBins] = {};
  double sum[kBins] = {};
  void add(float z) {
    if (z < ztop) {
      const int b = std::min(kBins - 1, int((z - zlo) * inv_w));
      ++count[b];
      sum[b] += z;
    }
  }
};

// Bins the heights z[j0..j1], one by one.
void bin_heights(const float* z, int j0, int j1, Histogram& h) {
  for (int j = j0; j <= j1; ++j) h.add(z[j]);
}

#if defined(__SSE2__)
// bin_heights four samples at a time: most are empty (+inf); the others are
// binned in the same order as one by one. Returns the first sample it did
// not do (bin_heights does the rest).
int bin_heights_sse2(const float* z, int j0, int j1, Histogram& h) {
  const __m128 top = _mm_set1_ps(h.ztop);
  int j = j0;
  for (; j + 3 <= j1; j += 4)
    for (int m = _mm_movemask_ps(_mm_cmplt_ps(_mm_loadu_ps(z + j), top)); m; m &= m - 1)
      h.add(z[j + __builtin_ctz(unsigned(m))]);
  return j;
}
#endif

// The mean penetration of one cell (m): max(0, lv - z) summed in float over
// its S x S samples (z: its first, rows `stride` apart), then / S^2.
float cell_mean(const float* z, std::size_t stride, int s, float lv, float inv_s2) {
  float acc = 0;
  for (int a = 0; a < s; ++a, z += stride)
    // max(lv - z, 0): lv - z where z < lv, else +0 (+inf: -inf -> 0), which
    // leaves acc as it is; without a branch.
    for (int b = 0; b < s; ++b) acc += std::max(lv - z[b], 0.0f);
  return acc * inv_s2;
}

}  // namespace

Foundation::Foundation(const SampleGrid& grid, double compliance_m, double max_sink_m)
    : grid_(grid),
      band_(float(compliance_m)),
      max_sink_(float(max_sink_m)),
      hit_(std::size_t(grid.cols), 0),
      cell0_(std::size_t(grid.mat.rows), 0),
      cell1_(std::size_t(grid.mat.rows), -1) {}

RowSpan Foundation::distribute(const DepthMap& d, double load_n, double stiffness_pa_per_m,
                               const Eigen::Vector2d* target, float* frame, FrameTrace* trace) {
  if (trace) *trace = FrameTrace{};
  if (!(d.zlo < band_) || !(load_n > 0)) return {};  // airborne, or nothing to carry
  if (!d.written() && !trace) return {};             // nothing on the mat: it reads 0
  const RowSpan rows = d.written() ? RowSpan{d.row0 / grid_.s, d.row1 / grid_.s} : RowSpan{};
  const double level = sink_level(d, load_n, stiffness_pa_per_m);
  const float lv = float(level);
  const Moments m = penetrate(d, lv, rows, frame);
  if (!(m.m0 > 0)) {  // no penetration: the frame stays 0
    const int C = grid_.mat.cols;
    for (int r = rows.first; r <= rows.last; ++r)
      if (cell0_[r] <= cell1_[r]) std::fill(frame + r * C + cell0_[r], frame + r * C + cell1_[r] + 1, 0.0f);
    return {};
  }
  const Tilt tilt = tilt_towards(m, target);
  const Load load = scale_to_load(d, lv, tilt, rows, load_n, frame);
  if (trace && load.total > 0) trace_feet(d, level, tilt, load, load_n, *trace);
  return rows;
}

// 1. Sink level s (m): sum over samples of max(0, s - z) = F / (k dA), from a
//    histogram of the sample heights within max_sink of the lowest point
//    (exact at bin edges, linear within a bin), samples off the mat included.
double Foundation::sink_level(const DepthMap& d, double load_n, double stiffness_pa_per_m) const {
  const float zlo = d.zlo, w = max_sink_ / kBins;
  Histogram h{zlo, zlo + max_sink_, 1.0f / w};
  for (int i = d.row0; i <= d.row1; ++i) {  // each row's written columns
    const float* z = &d.z[std::size_t(i) * grid_.cols];
    int j = d.span0[i];
#if defined(__SSE2__)
    j = bin_heights_sse2(z, j, d.span1[i], h);
#endif
    bin_heights(z, j, d.span1[i], h);
  }
  for (const OffSample& o : d.off) h.add(o.z);
  const double sample_area = grid_.ds * grid_.ds;
  const double target_sum = load_n / (stiffness_pa_per_m * sample_area);  // sum of (s - z), m
  double n = 0, s = 0;
  for (int b = 0; b < kBins; ++b) {
    n += h.count[b];
    s += h.sum[b];
    const double edge = zlo + (b + 1) * double(w);
    if (n > 0 && n * edge - s >= target_sum) return std::clamp((target_sum + s) / n, zlo + b * double(w), edge);
  }
  return h.ztop;  // the load needs more than the maximum sink
}

// 2. Mean penetration per cell (m) into frame, and its moments: the samples
//    off the mat (each a cell of its own), then the cells row by row.
Foundation::Moments Foundation::penetrate(const DepthMap& d, float lv, RowSpan rows, float* frame) {
  const float inv_s2 = 1.0f / float(grid_.s * grid_.s);
  Moments m;
  for (const OffSample& o : d.off)
    if (o.z < lv) m.add((lv - o.z) * inv_s2, grid_.sample_x(o.i), grid_.sample_y(o.j));
  for (int r = rows.first; r <= rows.last; ++r) penetrate_row(d, lv, r, frame, m);
  return m;
}

// Cells cell0[r] .. cell1[r] of row r hold every written sample of it; the
// others stay 0. hit[j]: some sample of column j of the cell row is below
// the level (the members in locals: the byte stores could alias them, and
// the loops then do not vectorise).
void Foundation::penetrate_row(const DepthMap& d, float lv, int r, float* frame, Moments& m) {
  unsigned char* __restrict hit = hit_.data();
  const int S = grid_.s;
  const std::size_t stride = std::size_t(grid_.cols);
  int js = grid_.cols, je1 = -1;
  for (int a = 0; a < S; ++a) js = std::min(js, d.span0[r * S + a]), je1 = std::max(je1, d.span1[r * S + a]);
  int& c0 = cell0_[r];
  int& c1 = cell1_[r];
  c0 = js / S, c1 = je1 < 0 ? -1 : je1 / S;
  if (c0 > c1) return;
  const int jb = c0 * S, je = (c1 + 1) * S;
  const float* __restrict z0 = &d.z[std::size_t(r * S) * stride];
  for (int j = jb; j < je; ++j) hit[j] = z0[j] < lv;
  for (int a = 1; a < S; ++a) {
    const float* __restrict za = z0 + std::size_t(a) * stride;
    for (int j = jb; j < je; ++j) hit[j] |= za[j] < lv;
  }
  const float inv_s2 = 1.0f / float(S * S);
  for (int c = c0; c <= c1; ++c) {
    unsigned char any = 0;
    for (int b = 0; b < S; ++b) any |= hit[c * S + b];
    if (!any) continue;  // no penetration: the cell stays 0
    const float p = cell_mean(z0 + c * S, stride, S, lv, inv_s2);
    frame[r * grid_.mat.cols + c] = p;
    if (p > 0) m.add(p, grid_.cell_x(r), grid_.cell_y(c));
  }
}

// 3. Tilt towards the target: weights 1 + g . (r - c) move the centre of
//    pressure by C g (C the penetration-weighted covariance of the contact).
Foundation::Tilt Foundation::tilt_towards(const Moments& m, const Eigen::Vector2d* target) const {
  Tilt t{Eigen::Vector2d(m.mx / m.m0, m.my / m.m0), Eigen::Vector2d::Zero()};
  if (!target) return t;
  const Eigen::Vector2d& c = t.centroid;
  const double pitch = grid_.mat.pitch_m;
  Eigen::Matrix2d cov;
  cov << m.mxx / m.m0 - c.x() * c.x(), m.mxy / m.m0 - c.x() * c.y(), m.mxy / m.m0 - c.x() * c.y(),
      m.myy / m.m0 - c.y() * c.y();
  cov += Eigen::Matrix2d::Identity() * (pitch * pitch / 12);  // a cell's own extent
  const Eigen::Matrix2d inv = cov.inverse();
  Eigen::Vector2d shift = *target - c;
  const double maha = std::sqrt(std::max(0.0, shift.dot(inv * shift)));
  if (maha > kMaxShift) shift *= kMaxShift / maha;
  t.g = inv * shift;
  return t;
}

// 4. Load scaling: each cell's penetration weighted by the tilt, and all
//    scaled so that the pressures x cell area sum to F, the samples off the
//    mat (weighted at their own centres) included.
Foundation::Load Foundation::scale_to_load(const DepthMap& d, float lv, const Tilt& tilt, RowSpan rows,
                                           double load_n, float* frame) const {
  const float inv_s2 = 1.0f / float(grid_.s * grid_.s);
  const int C = grid_.mat.cols;
  Load load;  // total: the sum of weighted cell penetrations, on and off the mat (m)
  for (const OffSample& o : d.off)
    if (o.z < lv) load.total += (lv - o.z) * inv_s2 * tilt.weight(grid_.sample_x(o.i), grid_.sample_y(o.j));
  for (int r = rows.first; r <= rows.last; ++r)
    for (int c = cell0_[r]; c <= cell1_[r]; ++c) {
      float& p = frame[r * C + c];
      if (p > 0) {
        p = float(p * tilt.weight(grid_.cell_x(r), grid_.cell_y(c)));
        load.total += p;
      }
    }
  load.scale = load.total > 0 ? load_n / (load.total * grid_.mat.cell_area_m2()) / 1000.0 : 0.0;  // kPa per m
  for (int r = rows.first; r <= rows.last; ++r)
    for (int c = cell0_[r]; c <= cell1_[r]; ++c) frame[r * C + c] = float(frame[r * C + c] * load.scale);
  return load;
}

// 5. Who carries what: per sample force = weighted penetration x scale x
//    sample area (the weight of its cell, as on the map; off the mat, of
//    its own centre), summed per sole (heel u < 0.3, forefoot u >= 0.6,
//    centre of pressure along u, contact area) and for the other parts.
void Foundation::trace_feet(const DepthMap& d, double level, const Tilt& tilt, const Load& load, double load_n,
                            FrameTrace& trace) const {
  const float lv = float(level);
  trace.load_n = load_n;
  trace.sink_m = level - d.zlo;
  const double sample_area = grid_.ds * grid_.ds;
  const double per_m = load.scale * 1000.0 * sample_area;  // N per m of sample penetration
  double cop[2] = {0, 0};
  auto add = [&](unsigned char owner, float z, float u, double wgt) {
    if (!(z < lv) || !(wgt > 0)) return;
    const double f = (lv - z) * per_m * wgt;
    if (owner == kLeftSole || owner == kRightSole) {
      FootLoad& fl = trace.foot[owner - 1];
      fl.force_n += f;
      fl.area_m2 += sample_area;
      cop[owner - 1] += f * u;
      if (u < 0.3f) fl.heel_n += f;
      if (u >= 0.6f) fl.forefoot_n += f;
    } else {
      trace.other_n += f;
    }
  };
  const int S = grid_.s;
  for (int i = d.row0; i <= d.row1; ++i)
    for (int j = d.span0[i]; j <= d.span1[i]; ++j) {
      const std::size_t k = std::size_t(i) * grid_.cols + j;
      add(d.owner[k], d.z[k], d.u[k], tilt.weight(grid_.cell_x(i / S), grid_.cell_y(j / S)));
    }
  for (std::size_t k = 0; k < d.off.size(); ++k)
    add(d.off_owner[k], d.off[k].z, d.off_u[k], tilt.weight(grid_.sample_x(d.off[k].i), grid_.sample_y(d.off[k].j)));
  for (int f = 0; f < 2; ++f)
    if (trace.foot[f].force_n > 0) trace.foot[f].cop_u = cop[f] / trace.foot[f].force_n;
}

}  // namespace ptnet::detail
