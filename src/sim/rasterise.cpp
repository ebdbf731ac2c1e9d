// Depth from below: the lowest body surface over S x S samples per mat cell,
// and each cell's mean penetration into the compliance band.
//
// Surfaces: the sole patches (a plane plus the soft-tissue height table of
// ptnet::SoleSurface, sampled analytically per sample) and the lower surfaces
// of the segment capsules (a chain of spheres along each tapered capsule,
// spaced at a third of the smaller radius: the envelope sags < r / 70).
// Only surfaces whose lowest point can reach the sink level are rasterised;
// a sole patch visits, row by row, only the samples its table spans.
#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "sim_internal.hpp"

namespace ptnet::detail {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
}

Rasteriser::Rasteriser(const MatSpec& mat, int subsamples, double compliance_m, double max_sink_m)
    : mat_(mat),
      s_(subsamples),
      band_(float(compliance_m)),
      max_sink_(float(max_sink_m)),
      reach_(float(compliance_m + max_sink_m)),
      ds_(mat.pitch_m / subsamples),
      half_l_(0.5 * mat.rows * mat.pitch_m),
      half_w_(0.5 * mat.cols * mat.pitch_m),
      ns_rows_(mat.rows * subsamples),
      ns_cols_(mat.cols * subsamples),
      zbuf_(std::size_t(ns_rows_) * ns_cols_, kInf),
      hit_(std::size_t(ns_cols_), 0),
      span0_(std::size_t(ns_rows_), ns_cols_),
      span1_(std::size_t(ns_rows_), -1),
      cell0_(std::size_t(mat.rows), 0),
      cell1_(std::size_t(mat.rows), -1) {
  di0_ = ns_rows_, di1_ = -1;
  zlo_ = kInf;
}

// Sample i has its centre at X = L/2 - (i + 0.5) ds.
void Rasteriser::row_range(double x0, double x1, int& lo, int& hi) const {
  lo = int(std::ceil((half_l_ - x1) / ds_ - 0.5));
  hi = int(std::floor((half_l_ - x0) / ds_ - 0.5));
}
void Rasteriser::col_range(double y0, double y1, int& lo, int& hi) const {
  lo = int(std::ceil((half_w_ - y1) / ds_ - 0.5));
  hi = int(std::floor((half_w_ - y0) / ds_ - 0.5));
}

void Rasteriser::touch(int i0, int i1, int j0, int j1) {
  i0 = std::max(i0, 0), i1 = std::min(i1, ns_rows_ - 1);
  j0 = std::max(j0, 0), j1 = std::min(j1, ns_cols_ - 1);
  if (i0 > i1 || j0 > j1) return;
  di0_ = std::min(di0_, i0), di1_ = std::max(di1_, i1);
  for (int i = i0; i <= i1; ++i) span0_[i] = std::min(span0_[i], j0), span1_[i] = std::max(span1_[i], j1);
}

namespace {
// floor(x) within +/- 1e9 (without a call to floor(); NaN: 1e9).
inline int floored(double x) {
  if (!(x > -1e9)) x = -1e9;
  if (!(x < 1e9)) x = 1e9;
  const int t = int(x);
  return t - (x < t);
}

// Narrows the integer range [lo, hi] of k to cover where lo_v <= c + a k <
// hi_v (inv_a = 1 / a). Conservative by a sample either side; the exact
// test runs per sample.
void clip_affine(double c, double a, double inv_a, double lo_v, double hi_v, int& lo, int& hi) {
  if (std::abs(a) < 1e-12) {
    if (!(c >= lo_v && c < hi_v)) hi = lo - 1;
    return;
  }
  double k0 = (lo_v - c) * inv_a, k1 = (hi_v - c) * inv_a;
  if (a < 0) std::swap(k0, k1);
  lo = std::max(lo, floored(k0) - 1);  // the first k >= k0 is ceil(k0) >= floor(k0)
  hi = std::min(hi, floored(k1) + 1);  // the last k < k1 (or <=) is <= floor(k1)
}
}  // namespace

bool Rasteriser::patch_box(const SoleSurface& sole, const SolePatch& p, int& i0, int& i1, int& j0, int& j1) const {
  if (p.up.z() < 0.2) return false;  // sole nearly vertical: its edge is not modelled
  // Corners of the patch on its plane; the profile only rises above it.
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, zmin = 1e300;
  for (double u : {p.u_begin, p.u_end}) {
    for (double v : {sole.v_min, sole.v_max}) {
      Eigen::Vector3d c = p.origin + p.forward * ((u - p.u_origin) * sole.length_m) +
                          p.left * (p.medial_sign * v * sole.width_m);
      x0 = std::min(x0, c.x()), x1 = std::max(x1, c.x());
      y0 = std::min(y0, c.y()), y1 = std::max(y1, c.y());
      zmin = std::min(zmin, c.z());
    }
  }
  if (zmin > reach_) return false;
  row_range(x0, x1, i0, i1);
  col_range(y0, y1, j0, j1);
  return i0 <= i1 && j0 <= j1;
}

bool Rasteriser::reaches_mat(const Body& body, const PosedBody& posed) const {
  auto on_mat = [&](int i0, int i1, int j0, int j1) {
    return i0 <= i1 && j0 <= j1 && i1 >= 0 && i0 < ns_rows_ && j1 >= 0 && j0 < ns_cols_;
  };
  int i0, i1, j0, j1;
  for (const auto* foot : {&posed.left_foot, &posed.right_foot})
    for (const SolePatch& p : *foot)
      if (patch_box(body.sole(), p, i0, i1, j0, j1) && on_mat(i0, i1, j0, j1)) return true;
  const auto& segs = body.segments();
  for (int s = 0; s < kSegmentCount; ++s) {
    if (!segs[s].touches_ground) continue;
    // Every sphere of capsule() lies within the ends' boxes' hull.
    const Eigen::Vector3d &a = posed.a[s], &b = posed.b[s];
    const double ra = segs[s].radius_a_m, rb = segs[s].radius_b_m;
    if (std::min(a.z() - ra, b.z() - rb) > reach_) continue;
    row_range(std::min(a.x() - ra, b.x() - rb), std::max(a.x() + ra, b.x() + rb), i0, i1);
    col_range(std::min(a.y() - ra, b.y() - rb), std::max(a.y() + ra, b.y() + rb), j0, j1);
    if (on_mat(i0, i1, j0, j1)) return true;
  }
  return false;
}

void Rasteriser::patch(const SoleSurface& sole, const SolePatch& p, Owner owner) {
  int i0, i1, j0, j1;
  if (!patch_box(sole, p, i0, i1, j0, j1)) return;
  const Eigen::Vector3d& n = p.up;

  // Affine maps from the sample position (X, Y) to the plane height z, the
  // table row fi (along u) and column fj (along v).
  const double ox = p.origin.x(), oy = p.origin.y(), oz = p.origin.z();
  const double zx = -n.x() / n.z(), zy = -n.y() / n.z();
  const double sx = p.forward.x() + p.forward.z() * zx, sy = p.forward.y() + p.forward.z() * zy;
  const double wx = p.left.x() + p.left.z() * zx, wy = p.left.y() + p.left.z() * zy;
  const double iu = (sole.nu - 1) / sole.length_m;                       // rows per metre along u
  const double iv = p.medial_sign * (sole.nv - 1) / ((sole.v_max - sole.v_min) * sole.width_m);
  const double fi0 = p.u_origin * (sole.nu - 1), fj0 = -sole.v_min / (sole.v_max - sole.v_min) * (sole.nv - 1);
  const double fi_lo = p.u_begin * (sole.nu - 1) - 0.5, fi_hi = p.u_end * (sole.nu - 1) + 0.5;
  const float inv_nz = float(1.0 / n.z());
  const float inv_nu = float(1.0 / (sole.nu - 1));
  const float* table = sole.height_m.data();
  const int nu = sole.nu, nv = sole.nv;
  // Along a row of samples, fi, fj and z change by a constant per sample.
  const double dfi = -iu * sy * ds_, dfj = -iv * wy * ds_, dz = -zy * ds_;
  const double inv_dfi = 1 / dfi, inv_dfj = 1 / dfj, inv_dz = 1 / dz;  // used where |d| >= 1e-12
  // Members in locals: the depth stores (float) could alias the float
  // members, which the loop would then reload per sample.
  const float reach = reach_;
  float zlo = zlo_;
  for (int i = i0; i <= i1; ++i) {
    const double dX = half_l_ - (i + 0.5) * ds_ - ox;
    const double dY0 = half_w_ - (j0 + 0.5) * ds_ - oy;
    // Values at j = j0 (then stepped by j - j0).
    const double fi_a = fi0 + iu * (sx * dX + sy * dY0);
    const double fj_a = fj0 + iv * (wx * dX + wy * dY0);
    const double z_a = oz + zx * dX + zy * dY0;
    int lo = 0, hi = j1 - j0;
    clip_affine(fi_a, dfi, inv_dfi, fi_lo, fi_hi, lo, hi);
    clip_affine(fj_a, dfj, inv_dfj, -0.5, nv - 0.5, lo, hi);
    // The table's heights are >= 0: where the plane alone is at or above
    // the reach, no sample can be recorded (kept: a sample either side).
    if (std::abs(dz) < 1e-12) {
      if (!(z_a < reach)) continue;
    } else {
      const int kz = floored((double(reach) - z_a) * inv_dz);  // the plane meets the reach
      if (dz > 0)
        hi = std::min(hi, kz + 1);
      else
        lo = std::max(lo, kz);
    }
    // The samples the exact tests below accept are one interval of k: fi
    // and fj are monotone in k (in floating point too), and each test is a
    // threshold on one of them. Narrowed to it from both ends (a sample or
    // two: the clips above are conservative by one), the loops test nothing
    // per sample.
    auto on_table = [&](int k) {
      const double fi = fi_a + dfi * k;
      if (fi < fi_lo || fi >= fi_hi) return false;
      const double fj = fj_a + dfj * k;
      const int ti = int(fi + 0.5), tj = int(fj + 0.5);
      return ti >= 0 && ti < nu && fj >= -0.5 && tj < nv;
    };
    while (lo <= hi && !on_table(lo)) ++lo;
    while (hi >= lo && !on_table(hi)) --hi;
    if (lo > hi) continue;
    touch(i, i, j0 + lo, j0 + hi);
    auto height = [&](int k, double& fi) {
      fi = fi_a + dfi * k;
      const double fj = fj_a + dfj * k;
      return table[std::size_t(int(fi + 0.5)) * nv + std::size_t(int(fj + 0.5))];
    };
    // Samples off the mat (or every sample, with a trace): record().
    auto record_each = [&](int k0, int k1) {
      for (int k = k0; k <= k1; ++k) {
        double fi;
        const float h = height(k, fi);
        if (h < SoleSurface::kOutside) {
          zlo_ = zlo;
          record(i, j0 + k, float(z_a + dz * k) + h * inv_nz, owner, float(fi) * inv_nu);
          zlo = zlo_;
        }
      }
    };
    const bool row_on = i >= 0 && i < ns_rows_ && !trace_;
    if (!row_on) {
      record_each(lo, hi);
      continue;
    }
    // Samples on the mat, k in [on_lo, on_hi]: record(), inlined and without
    // branches; a height out of reach (kOutside, off the foot, included)
    // becomes +inf, which changes nothing.
    const int on_lo = std::max(lo, -j0), on_hi = std::min(hi, ns_cols_ - 1 - j0);
    record_each(lo, std::min(hi, on_lo - 1));
    float* const zrow = zbuf_.data() + std::size_t(i) * ns_cols_;
    int k = on_lo;
#if defined(__SSE2__)
    // Four samples at a time: the same operations on each (IEEE, no FMA),
    // the table read one by one; _mm_min_ps(b, a) is std::min(a, b).
    if (on_hi - on_lo >= 3) {
      const __m128d vfi_a = _mm_set1_pd(fi_a), vfj_a = _mm_set1_pd(fj_a), vz_a = _mm_set1_pd(z_a);
      const __m128d vdfi = _mm_set1_pd(dfi), vdfj = _mm_set1_pd(dfj), vdz = _mm_set1_pd(dz);
      const __m128d half = _mm_set1_pd(0.5), two = _mm_set1_pd(2.0);
      const __m128 vinv_nz = _mm_set1_ps(inv_nz), vreach = _mm_set1_ps(reach), vinf = _mm_set1_ps(kInf);
      __m128 vzlo = _mm_set1_ps(zlo);
      __m128d k01 = _mm_set_pd(double(k + 1), double(k));  // lanes k, k + 1
      alignas(16) int ti[4], tj[4];
      for (; k + 3 <= on_hi; k += 4) {
        const __m128d k23 = _mm_add_pd(k01, two);
        const __m128d fi01 = _mm_add_pd(vfi_a, _mm_mul_pd(vdfi, k01)), fi23 = _mm_add_pd(vfi_a, _mm_mul_pd(vdfi, k23));
        const __m128d fj01 = _mm_add_pd(vfj_a, _mm_mul_pd(vdfj, k01)), fj23 = _mm_add_pd(vfj_a, _mm_mul_pd(vdfj, k23));
        _mm_store_si128(reinterpret_cast<__m128i*>(ti),
                        _mm_unpacklo_epi64(_mm_cvttpd_epi32(_mm_add_pd(fi01, half)),
                                           _mm_cvttpd_epi32(_mm_add_pd(fi23, half))));
        _mm_store_si128(reinterpret_cast<__m128i*>(tj),
                        _mm_unpacklo_epi64(_mm_cvttpd_epi32(_mm_add_pd(fj01, half)),
                                           _mm_cvttpd_epi32(_mm_add_pd(fj23, half))));
        const __m128 h = _mm_set_ps(table[std::size_t(ti[3]) * nv + std::size_t(tj[3])],
                                    table[std::size_t(ti[2]) * nv + std::size_t(tj[2])],
                                    table[std::size_t(ti[1]) * nv + std::size_t(tj[1])],
                                    table[std::size_t(ti[0]) * nv + std::size_t(tj[0])]);
        const __m128 plane = _mm_movelh_ps(_mm_cvtpd_ps(_mm_add_pd(vz_a, _mm_mul_pd(vdz, k01))),
                                           _mm_cvtpd_ps(_mm_add_pd(vz_a, _mm_mul_pd(vdz, k23))));
        const __m128 z = _mm_add_ps(plane, _mm_mul_ps(h, vinv_nz));
        const __m128 below = _mm_cmplt_ps(z, vreach);
        const __m128 zr = _mm_or_ps(_mm_and_ps(below, z), _mm_andnot_ps(below, vinf));
        vzlo = _mm_min_ps(zr, vzlo);
        float* const dst = zrow + j0 + k;
        _mm_storeu_ps(dst, _mm_min_ps(zr, _mm_loadu_ps(dst)));
        k01 = _mm_add_pd(k23, two);
      }
      alignas(16) float lanes[4];
      _mm_store_ps(lanes, vzlo);
      for (float l : lanes) zlo = std::min(zlo, l);
    }
#endif
    for (; k <= on_hi; ++k) {
      double fi;
      const float h = height(k, fi);
      const float z = float(z_a + dz * k) + h * inv_nz;
      const float zr = z < reach ? z : kInf;
      zlo = std::min(zlo, zr);
      zrow[j0 + k] = std::min(zrow[j0 + k], zr);
    }
    record_each(std::max(lo, on_hi + 1), hi);
  }
  zlo_ = zlo;
}

void Rasteriser::sphere(double cx, double cy, double cz, double r) {
  if (cz - r > reach_) return;
  const double r2 = r * r;
  // Only the disc where the lower surface is below the reach can be
  // recorded (its radius rr, plus a sample: the exact test is per sample).
  const double above = cz - double(reach_);
  const double rr = (above > 0 ? std::sqrt(std::max(0.0, r2 - above * above)) : r) + ds_;
  int i0, i1, j0, j1;
  row_range(cx - std::min(r, rr), cx + std::min(r, rr), i0, i1);
  col_range(cy - std::min(r, rr), cy + std::min(r, rr), j0, j1);
  if (i0 > i1 || j0 > j1) return;
  touch(i0, i1, j0, j1);
  for (int i = i0; i <= i1; ++i) {
    const double dx = half_l_ - (i + 0.5) * ds_ - cx;
    for (int j = j0; j <= j1; ++j) {
      const double dy = half_w_ - (j + 0.5) * ds_ - cy;
      const double d2 = dx * dx + dy * dy;
      if (d2 < r2) record(i, j, float(cz - std::sqrt(r2 - d2)), kOther, 0.0f);
    }
  }
}

void Rasteriser::capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra, double rb) {
  if (std::min(a.z() - ra, b.z() - rb) > reach_) return;
  const double len = (b - a).norm();
  const int n = 1 + int(std::ceil(len / (std::min(ra, rb) / 3)));
  for (int k = 0; k <= n; ++k) {
    const double t = double(k) / n;
    const Eigen::Vector3d c = a + t * (b - a);
    const double r = ra + t * (rb - ra);
    if (c.z() - r > reach_) continue;
    sphere(c.x(), c.y(), c.z(), r);
  }
}

void Rasteriser::rasterise(const Body& body, const PosedBody& posed, bool trace) {
  trace_ = trace;
  if (trace_ && owner_.empty()) {
    owner_.assign(zbuf_.size(), kNone);
    ubuf_.assign(zbuf_.size(), 0.0f);
  }
  // Off the mat the frame reads 0 whatever the load: without a trace (which
  // reports the load off the mat too) there is nothing to rasterise.
  if (!trace_ && !reaches_mat(body, posed)) return;
  for (const auto& p : posed.left_foot) patch(body.sole(), p, kLeftSole);
  for (const auto& p : posed.right_foot) patch(body.sole(), p, kRightSole);
  const auto& segs = body.segments();
  for (int s = 0; s < kSegmentCount; ++s)
    if (segs[s].touches_ground) capsule(posed.a[s], posed.b[s], segs[s].radius_a_m, segs[s].radius_b_m);
}

void Rasteriser::clear() {
  for (int i = di0_; i <= di1_; ++i) {
    if (span0_[i] <= span1_[i])
      std::fill(&zbuf_[std::size_t(i) * ns_cols_ + span0_[i]], &zbuf_[std::size_t(i) * ns_cols_ + span1_[i]] + 1, kInf);
    span0_[i] = ns_cols_, span1_[i] = -1;
  }
  di0_ = ns_rows_, di1_ = -1;
  zlo_ = kInf;
  off_.clear();
  off_u_.clear();
  off_owner_.clear();
}

RowSpan Rasteriser::distribute(double load_n, double stiffness_pa_per_m, const Eigen::Vector2d* target,
                               float* frame, FrameTrace* trace) {
  if (trace) *trace = FrameTrace{};
  if (!(zlo_ < band_) || !(load_n > 0)) {  // airborne, or nothing to carry
    clear();
    return {};
  }
  const bool dirty = di1_ >= di0_;  // some sample on the mat was written
  if (!dirty && !trace) {  // nothing on the mat: it reads 0
    clear();
    return {};
  }
  const int r0 = dirty ? di0_ / s_ : 0, r1 = dirty ? di1_ / s_ : -1;
  const double pitch = mat_.pitch_m;
  auto cell_x = [&](int r) { return half_l_ - (r + 0.5) * pitch; };
  auto cell_y = [&](int c) { return half_w_ - (c + 0.5) * pitch; };
  auto sample_x = [&](int i) { return half_l_ - (i + 0.5) * ds_; };
  auto sample_y = [&](int j) { return half_w_ - (j + 0.5) * ds_; };

  // 1. Sink level s: sum over samples of max(0, s - z) = F / (k dA), from a
  //    histogram of the sample heights within max_sink of the lowest point
  //    (exact at bin edges, linear within a bin).
  constexpr int kBins = 64;
  const float zlo = zlo_, w = max_sink_ / kBins, inv_w = 1.0f / w, ztop = zlo + max_sink_;
  int count[kBins] = {};
  double sum[kBins] = {};
  auto bin = [&](float z) {
    if (z < ztop) {
      const int b = std::min(kBins - 1, int((z - zlo) * inv_w));
      ++count[b];
      sum[b] += z;
    }
  };
  for (int i = di0_; i <= di1_; ++i) {  // each row's written columns
    const float* z = &zbuf_[std::size_t(i) * ns_cols_];
    int j = span0_[i];
    const int j1 = span1_[i];
#if defined(__SSE2__)
    // Four samples at a time: most are empty (+inf); the others are binned
    // in the same order as one by one.
    const __m128 top = _mm_set1_ps(ztop);
    for (; j + 3 <= j1; j += 4)
      for (int m = _mm_movemask_ps(_mm_cmplt_ps(_mm_loadu_ps(z + j), top)); m; m &= m - 1)
        bin(z[j + __builtin_ctz(unsigned(m))]);
#endif
    for (; j <= j1; ++j) bin(z[j]);
  }
  for (const OffSample& o : off_) bin(o.z);
  const double sample_area = ds_ * ds_;
  const double target_sum = load_n / (stiffness_pa_per_m * sample_area);  // sum of (s - z), m
  double level = ztop, n = 0, s = 0;
  for (int b = 0; b < kBins; ++b) {
    n += count[b];
    s += sum[b];
    const double edge = zlo + (b + 1) * double(w);
    if (n > 0 && n * edge - s >= target_sum) {
      level = std::clamp((target_sum + s) / n, zlo + b * double(w), edge);
      break;
    }
  }
  const float lv = float(level);

  // 2. Mean penetration per cell (m), and its moments for the tilt.
  const float inv_s2 = 1.0f / float(s_ * s_);
  double m0 = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
  auto moment = [&](double p, double x, double y) {
    m0 += p, mx += p * x, my += p * y, mxx += p * x * x, mxy += p * x * y, myy += p * y * y;
  };
  for (const OffSample& o : off_)
    if (o.z < lv) moment((lv - o.z) * inv_s2, sample_x(o.i), sample_y(o.j));
  // hit[j]: some sample of column j of the cell row is below the level (the
  // members in locals: the byte stores could alias them, and the loops then
  // do not vectorise).
  // Cells cell0[r] .. cell1[r] of row r hold every written sample of it;
  // the others stay 0.
  unsigned char* __restrict hit = hit_.data();
  int* const cell0 = cell0_.data();
  int* const cell1 = cell1_.data();
  const int S = s_;
  const std::size_t stride = std::size_t(ns_cols_);
  for (int r = r0; r <= r1; ++r) {
    int js = ns_cols_, je1 = -1;
    for (int a = 0; a < S; ++a) js = std::min(js, span0_[r * S + a]), je1 = std::max(je1, span1_[r * S + a]);
    cell0[r] = js / S, cell1[r] = je1 < 0 ? -1 : je1 / S;
    if (cell0[r] > cell1[r]) continue;
    const int jb = cell0[r] * S, je = (cell1[r] + 1) * S;
    const float* __restrict z0 = &zbuf_[std::size_t(r * S) * stride];
    for (int j = jb; j < je; ++j) hit[j] = z0[j] < lv;
    for (int a = 1; a < S; ++a) {
      const float* __restrict za = z0 + std::size_t(a) * stride;
      for (int j = jb; j < je; ++j) hit[j] |= za[j] < lv;
    }
    for (int c = cell0[r]; c <= cell1[r]; ++c) {
      unsigned char any = 0;
      for (int b = 0; b < S; ++b) any |= hit[c * S + b];
      if (!any) continue;  // no penetration: the cell stays 0
      float acc = 0;
      for (int a = 0; a < s_; ++a) {
        const float* z = &zbuf_[std::size_t(r * s_ + a) * ns_cols_ + c * s_];
        // max(lv - z, 0): lv - z where z < lv, else +0 (+inf: -inf -> 0),
        // which leaves acc as it is; without a branch.
        for (int b = 0; b < s_; ++b) acc += std::max(lv - z[b], 0.0f);
      }
      acc *= inv_s2;
      frame[r * mat_.cols + c] = acc;
      if (acc > 0) moment(acc, cell_x(r), cell_y(c));
    }
  }
  if (!(m0 > 0)) {
    for (int r = r0; r <= r1; ++r)
      if (cell0[r] <= cell1[r]) std::fill(frame + r * mat_.cols + cell0[r], frame + r * mat_.cols + cell1[r] + 1, 0.0f);
    clear();
    return {};
  }

  // 3. Tilt towards the target: weights 1 + g . (r - c) move the centre of
  //    pressure by C g (C the penetration-weighted covariance of the contact).
  const Eigen::Vector2d centroid(mx / m0, my / m0);
  Eigen::Vector2d tilt = Eigen::Vector2d::Zero();
  if (target) {
    Eigen::Matrix2d cov;
    cov << mxx / m0 - centroid.x() * centroid.x(), mxy / m0 - centroid.x() * centroid.y(),
        mxy / m0 - centroid.x() * centroid.y(), myy / m0 - centroid.y() * centroid.y();
    cov += Eigen::Matrix2d::Identity() * (pitch * pitch / 12);  // a cell's own extent
    const Eigen::Matrix2d inv = cov.inverse();
    Eigen::Vector2d shift = *target - centroid;
    const double maha = std::sqrt(std::max(0.0, shift.dot(inv * shift)));
    constexpr double kMaxShift = 0.6;  // standard deviations: every contact cell keeps some load
    if (maha > kMaxShift) shift *= kMaxShift / maha;
    tilt = inv * shift;
  }
  auto weight = [&](double x, double y) {
    return std::max(0.0, 1.0 + tilt.x() * (x - centroid.x()) + tilt.y() * (y - centroid.y()));
  };
  double total = 0;  // sum of weighted cell penetrations, on and off the mat (m)
  for (const OffSample& o : off_)
    if (o.z < lv) total += (lv - o.z) * inv_s2 * weight(sample_x(o.i), sample_y(o.j));
  for (int r = r0; r <= r1; ++r)
    for (int c = cell0[r]; c <= cell1[r]; ++c) {
      float& p = frame[r * mat_.cols + c];
      if (p > 0) {
        p = float(p * weight(cell_x(r), cell_y(c)));
        total += p;
      }
    }
  const double scale = total > 0 ? load_n / (total * mat_.cell_area_m2()) / 1000.0 : 0.0;  // kPa per m
  for (int r = r0; r <= r1; ++r)
    for (int c = cell0[r]; c <= cell1[r]; ++c) frame[r * mat_.cols + c] = float(frame[r * mat_.cols + c] * scale);

  // 4. Who carries what (trace): per sample force = weighted penetration x
  //    scale x sample area (the weight of its cell, as on the map).
  if (trace && total > 0) {
    trace->load_n = load_n;
    trace->sink_m = level - zlo;
    const double per_m = scale * 1000.0 * sample_area;  // N per m of sample penetration
    double cop[2] = {0, 0};
    auto add = [&](unsigned char owner, float z, float u, double wgt) {
      if (!(z < lv) || !(wgt > 0)) return;
      const double f = (lv - z) * per_m * wgt;
      if (owner == kLeftSole || owner == kRightSole) {
        FootLoad& fl = trace->foot[owner - 1];
        fl.force_n += f;
        fl.area_m2 += sample_area;
        cop[owner - 1] += f * u;
        if (u < 0.3f) fl.heel_n += f;
        if (u >= 0.6f) fl.forefoot_n += f;
      } else {
        trace->other_n += f;
      }
    };
    for (int i = di0_; i <= di1_; ++i)
      for (int j = span0_[i]; j <= span1_[i]; ++j) {
        const std::size_t k = std::size_t(i) * ns_cols_ + j;
        add(owner_[k], zbuf_[k], ubuf_[k], weight(cell_x(i / s_), cell_y(j / s_)));
      }
    for (std::size_t k = 0; k < off_.size(); ++k)
      add(off_owner_[k], off_[k].z, off_u_[k], weight(sample_x(off_[k].i), sample_y(off_[k].j)));
    for (int f = 0; f < 2; ++f)
      if (trace->foot[f].force_n > 0) trace->foot[f].cop_u = cop[f] / trace->foot[f].force_n;
  }
  clear();
  return {r0, r1};
}

}  // namespace ptnet::detail
