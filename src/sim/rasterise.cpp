// Depth from below (Rasteriser): the lowest body surface over S x S
// samples per mat cell, on and off the mat, for the elastic foundation
// (foundation.cpp) to sink into.
//
// Surfaces: the sole patches (a plane plus the soft-tissue height table of
// ptnet::SoleSurface, sampled analytically per sample) and the lower surfaces
// of the segment capsules (a chain of spheres along each tapered capsule,
// spaced at a third of the smaller radius: the envelope sags < r / 70).
// Only surfaces whose lowest point can reach the sink level are rasterised;
// a sole patch visits, row by row, only the samples its table spans, the
// samples on the mat four at a time (depth_samples_sse2, beside its scalar
// twin depth_samples).
#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "sim_internal.hpp"

namespace ptnet::detail {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
}

SampleGrid::SampleGrid(const MatSpec& mat, int subsamples)
    : mat(mat),
      s(subsamples),
      ds(mat.pitch_m / subsamples),
      half_l(0.5 * mat.rows * mat.pitch_m),
      half_w(0.5 * mat.cols * mat.pitch_m),
      rows(mat.rows * subsamples),
      cols(mat.cols * subsamples) {}

DepthMap::DepthMap(const SampleGrid& grid)
    : grid(grid),
      z(std::size_t(grid.rows) * grid.cols, kInf),
      row0(grid.rows),
      row1(-1),
      span0(std::size_t(grid.rows), grid.cols),
      span1(std::size_t(grid.rows), -1),
      zlo(kInf) {}

Rasteriser::Rasteriser(const MatSpec& mat, int subsamples, double reach_m)
    : reach_(float(reach_m)), d_(SampleGrid(mat, subsamples)) {}

// Sample i has its centre at X = L/2 - (i + 0.5) ds.
void Rasteriser::row_range(double x0, double x1, int& lo, int& hi) const {
  lo = int(std::ceil((d_.grid.half_l - x1) / d_.grid.ds - 0.5));
  hi = int(std::floor((d_.grid.half_l - x0) / d_.grid.ds - 0.5));
}
void Rasteriser::col_range(double y0, double y1, int& lo, int& hi) const {
  lo = int(std::ceil((d_.grid.half_w - y1) / d_.grid.ds - 0.5));
  hi = int(std::floor((d_.grid.half_w - y0) / d_.grid.ds - 0.5));
}

void Rasteriser::touch(int i0, int i1, int j0, int j1) {
  i0 = std::max(i0, 0), i1 = std::min(i1, d_.grid.rows - 1);
  j0 = std::max(j0, 0), j1 = std::min(j1, d_.grid.cols - 1);
  if (i0 > i1 || j0 > j1) return;
  d_.row0 = std::min(d_.row0, i0), d_.row1 = std::max(d_.row1, i1);
  for (int i = i0; i <= i1; ++i) d_.span0[i] = std::min(d_.span0[i], j0), d_.span1[i] = std::max(d_.span1[i], j1);
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

// A sole patch's affine maps from a sample's position (X, Y) to the plane
// height z, the table row fi (along u) and column fj (along v). Along a row
// of samples each changes by a constant per sample (dz, dfi, dfj).
struct PatchMap {
  PatchMap(const SoleSurface& sole, const SolePatch& p, double ds) {
    const Eigen::Vector3d& n = p.up;
    ox = p.origin.x(), oy = p.origin.y(), oz = p.origin.z();
    zx = -n.x() / n.z(), zy = -n.y() / n.z();
    sx = p.forward.x() + p.forward.z() * zx, sy = p.forward.y() + p.forward.z() * zy;
    wx = p.left.x() + p.left.z() * zx, wy = p.left.y() + p.left.z() * zy;
    iu = (sole.nu - 1) / sole.length_m;  // rows per metre along u
    iv = p.medial_sign * (sole.nv - 1) / ((sole.v_max - sole.v_min) * sole.width_m);
    fi0 = p.u_origin * (sole.nu - 1), fj0 = -sole.v_min / (sole.v_max - sole.v_min) * (sole.nv - 1);
    fi_lo = p.u_begin * (sole.nu - 1) - 0.5, fi_hi = p.u_end * (sole.nu - 1) + 0.5;
    inv_nz = float(1.0 / n.z());
    inv_nu = float(1.0 / (sole.nu - 1));
    table = sole.height_m.data();
    nu = sole.nu, nv = sole.nv;
    dfi = -iu * sy * ds, dfj = -iv * wy * ds, dz = -zy * ds;
    inv_dfi = 1 / dfi, inv_dfj = 1 / dfj, inv_dz = 1 / dz;  // used where |d| >= 1e-12
  }
  double ox, oy, oz;          // the patch's origin (m)
  double zx, zy;              // plane height per m of X, Y
  double sx, sy, wx, wy;      // forward and left offsets along the plane per m of X, Y
  double iu, iv, fi0, fj0;    // table rows and columns per m along forward and left; at the origin
  double fi_lo, fi_hi;        // the rows the patch covers, half a row either side
  float inv_nz, inv_nu;       // 1 / up.z, 1 / (nu - 1)
  const float* table;         // SoleSurface::height_m [nu, nv]
  int nu, nv;
  double dfi, dfj, dz;        // per sample along a row
  double inv_dfi, inv_dfj, inv_dz;
};

// One row of samples of a patch: its values at the row's first sample j0
// (then stepped by k = j - j0) and the samples [lo, hi] it records.
struct PatchRow {
  double fi_a, fj_a, z_a;
  int lo, hi;

  // Whether sample k maps onto the patch's rows and the table.
  bool on_table(const PatchMap& m, int k) const {
    const double fi = fi_a + m.dfi * k;
    if (fi < m.fi_lo || fi >= m.fi_hi) return false;
    const double fj = fj_a + m.dfj * k;
    const int ti = int(fi + 0.5), tj = int(fj + 0.5);
    return ti >= 0 && ti < m.nu && fj >= -0.5 && tj < m.nv;
  }
  // The table height at sample k (m above the plane; kOutside: not foot), and its row fi.
  float height(const PatchMap& m, int k, double& fi) const {
    fi = fi_a + m.dfi * k;
    const double fj = fj_a + m.dfj * k;
    return m.table[std::size_t(int(fi + 0.5)) * m.nv + std::size_t(int(fj + 0.5))];
  }
};

namespace {

// The row of a patch whose first sample j0 lies at (dX, dY0) from the
// patch's origin, and the samples k in [0, width] it records: those on the
// patch's table whose plane is below the reach. False when there are none.
bool patch_row(const PatchMap& m, double dX, double dY0, int width, float reach, PatchRow& row) {
  row.fi_a = m.fi0 + m.iu * (m.sx * dX + m.sy * dY0);
  row.fj_a = m.fj0 + m.iv * (m.wx * dX + m.wy * dY0);
  row.z_a = m.oz + m.zx * dX + m.zy * dY0;
  int lo = 0, hi = width;
  clip_affine(row.fi_a, m.dfi, m.inv_dfi, m.fi_lo, m.fi_hi, lo, hi);
  clip_affine(row.fj_a, m.dfj, m.inv_dfj, -0.5, m.nv - 0.5, lo, hi);
  // The table's heights are >= 0: where the plane alone is at or above
  // the reach, no sample can be recorded (kept: a sample either side).
  if (std::abs(m.dz) < 1e-12) {
    if (!(row.z_a < reach)) return false;
  } else {
    const int kz = floored((double(reach) - row.z_a) * m.inv_dz);  // the plane meets the reach
    if (m.dz > 0)
      hi = std::min(hi, kz + 1);
    else
      lo = std::max(lo, kz);
  }
  // The samples the exact tests accept are one interval of k: fi and fj
  // are monotone in k (in floating point too), and each test is a
  // threshold on one of them. Narrowed to it from both ends (a sample or
  // two: the clips above are conservative by one), the loops test nothing
  // per sample.
  while (lo <= hi && !row.on_table(m, lo)) ++lo;
  while (hi >= lo && !row.on_table(m, hi)) --hi;
  row.lo = lo, row.hi = hi;
  return lo <= hi;
}

// Samples k in [k0, k1] of a patch row on the mat (zrow: the sample row,
// the row's first sample at j0), one by one: each keeps the lowest of its
// height and the patch's; a height out of reach (kOutside, off the foot,
// included) becomes +inf, which changes nothing. zlo: the lowest so far.
void depth_samples(const PatchMap& m, const PatchRow& row, int k0, int k1, float* zrow, int j0, float reach,
                   float& zlo) {
  const float inv_nz = m.inv_nz;
  float lowest = zlo;
  for (int k = k0; k <= k1; ++k) {
    double fi;
    const float h = row.height(m, k, fi);
    const float z = float(row.z_a + m.dz * k) + h * inv_nz;
    const float zr = z < reach ? z : kInf;
    lowest = std::min(lowest, zr);
    zrow[j0 + k] = std::min(zrow[j0 + k], zr);
  }
  zlo = lowest;
}

#if defined(__SSE2__)
// depth_samples four samples at a time: the same operations on each (IEEE,
// no FMA), the table read one by one; _mm_min_ps(b, a) is std::min(a, b).
// Returns the first sample it did not do (depth_samples does the rest).
int depth_samples_sse2(const PatchMap& m, const PatchRow& row, int k, int k1, float* zrow, int j0, float reach,
                       float& zlo) {
  if (k1 - k < 3) return k;
  const float* table = m.table;
  const int nv = m.nv;
  const __m128d vfi_a = _mm_set1_pd(row.fi_a), vfj_a = _mm_set1_pd(row.fj_a), vz_a = _mm_set1_pd(row.z_a);
  const __m128d vdfi = _mm_set1_pd(m.dfi), vdfj = _mm_set1_pd(m.dfj), vdz = _mm_set1_pd(m.dz);
  const __m128d half = _mm_set1_pd(0.5), two = _mm_set1_pd(2.0);
  const __m128 vinv_nz = _mm_set1_ps(m.inv_nz), vreach = _mm_set1_ps(reach), vinf = _mm_set1_ps(kInf);
  __m128 vzlo = _mm_set1_ps(zlo);
  __m128d k01 = _mm_set_pd(double(k + 1), double(k));  // lanes k, k + 1
  alignas(16) int ti[4], tj[4];
  for (; k + 3 <= k1; k += 4) {
    const __m128d k23 = _mm_add_pd(k01, two);
    const __m128d fi01 = _mm_add_pd(vfi_a, _mm_mul_pd(vdfi, k01)), fi23 = _mm_add_pd(vfi_a, _mm_mul_pd(vdfi, k23));
    const __m128d fj01 = _mm_add_pd(vfj_a, _mm_mul_pd(vdfj, k01)), fj23 = _mm_add_pd(vfj_a, _mm_mul_pd(vdfj, k23));
    _mm_store_si128(reinterpret_cast<__m128i*>(ti), _mm_unpacklo_epi64(_mm_cvttpd_epi32(_mm_add_pd(fi01, half)),
                                                                       _mm_cvttpd_epi32(_mm_add_pd(fi23, half))));
    _mm_store_si128(reinterpret_cast<__m128i*>(tj), _mm_unpacklo_epi64(_mm_cvttpd_epi32(_mm_add_pd(fj01, half)),
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
    float* const dst = zrow + (j0 + k);
    _mm_storeu_ps(dst, _mm_min_ps(zr, _mm_loadu_ps(dst)));
    k01 = _mm_add_pd(k23, two);
  }
  alignas(16) float lanes[4];
  _mm_store_ps(lanes, vzlo);
  for (float l : lanes) zlo = std::min(zlo, l);
  return k;
}
#endif

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
    return i0 <= i1 && j0 <= j1 && i1 >= 0 && i0 < d_.grid.rows && j1 >= 0 && j0 < d_.grid.cols;
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
  const SampleGrid& g = d_.grid;
  const PatchMap m(sole, p, g.ds);
  for (int i = i0; i <= i1; ++i) {
    PatchRow row;
    if (!patch_row(m, g.half_l - (i + 0.5) * g.ds - m.ox, g.half_w - (j0 + 0.5) * g.ds - m.oy, j1 - j0, reach_, row))
      continue;
    touch(i, i, j0 + row.lo, j0 + row.hi);
    // Samples off the mat (or every sample, with a trace): record().
    if (!(i >= 0 && i < g.rows) || trace_) {
      record_samples(m, row, i, j0, row.lo, row.hi, owner);
      continue;
    }
    // Samples on the mat, k in [on_lo, on_hi]: record(), inlined and without
    // branches.
    const int on_lo = std::max(row.lo, -j0), on_hi = std::min(row.hi, g.cols - 1 - j0);
    record_samples(m, row, i, j0, row.lo, std::min(row.hi, on_lo - 1), owner);
    float* const zrow = d_.z.data() + std::size_t(i) * g.cols;
    float zlo = d_.zlo;
    int k = on_lo;
#if defined(__SSE2__)
    k = depth_samples_sse2(m, row, k, on_hi, zrow, j0, reach_, zlo);
#endif
    depth_samples(m, row, k, on_hi, zrow, j0, reach_, zlo);
    d_.zlo = zlo;
    record_samples(m, row, i, j0, std::max(row.lo, on_hi + 1), row.hi, owner);
  }
}

void Rasteriser::record_samples(const PatchMap& m, const PatchRow& row, int i, int j0, int k0, int k1, Owner owner) {
  for (int k = k0; k <= k1; ++k) {
    double fi;
    const float h = row.height(m, k, fi);
    if (h < SoleSurface::kOutside)
      record(i, j0 + k, float(row.z_a + m.dz * k) + h * m.inv_nz, owner, float(fi) * m.inv_nu);
  }
}

void Rasteriser::sphere(double cx, double cy, double cz, double r) {
  if (cz - r > reach_) return;
  const double r2 = r * r;
  // Only the disc where the lower surface is below the reach can be
  // recorded (its radius rr, plus a sample: the exact test is per sample).
  const double above = cz - double(reach_);
  const double rr = (above > 0 ? std::sqrt(std::max(0.0, r2 - above * above)) : r) + d_.grid.ds;
  int i0, i1, j0, j1;
  row_range(cx - std::min(r, rr), cx + std::min(r, rr), i0, i1);
  col_range(cy - std::min(r, rr), cy + std::min(r, rr), j0, j1);
  if (i0 > i1 || j0 > j1) return;
  touch(i0, i1, j0, j1);
  for (int i = i0; i <= i1; ++i) {
    const double dx = d_.grid.half_l - (i + 0.5) * d_.grid.ds - cx;
    for (int j = j0; j <= j1; ++j) {
      const double dy = d_.grid.half_w - (j + 0.5) * d_.grid.ds - cy;
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
  clear();
  trace_ = trace;
  if (trace_ && d_.owner.empty()) {
    d_.owner.assign(d_.z.size(), kNone);
    d_.u.assign(d_.z.size(), 0.0f);
  }
  // Off the mat the frame reads 0 whatever the load: without a trace (which
  // reports the load off the mat too) there is nothing to rasterise.
  if (!trace_ && !reaches_mat(body, posed)) return;
  for (const auto& p : posed.left_foot) patch(body.sole(), p, kLeftSole);
  for (const auto& p : posed.right_foot) patch(body.sole(), p, kRightSole);
  const auto& segs = body.segments();
  for (int s = 0; s < kSegmentCount; ++s)
    if (segs[s].touches_ground) capsule(posed.a[s], posed.b[s], segs[s].radius_a_m, segs[s].radius_b_m);
  keep_lowest_off_mat();
}

// Off the mat as on it, a position keeps its lowest surface (the first
// recorded of equal heights): a capsule's overlapping spheres, or two sole
// patches along their seam, record one position several times.
void Rasteriser::keep_lowest_off_mat() {
  if (d_.off.size() < 2) return;
  auto& idx = off_order_;
  idx.resize(d_.off.size());
  for (std::size_t k = 0; k < idx.size(); ++k) idx[k] = k;
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    const OffSample &p = d_.off[a], &q = d_.off[b];
    return p.i != q.i ? p.i < q.i : p.j != q.j ? p.j < q.j : p.z < q.z;
  });
  std::size_t n = 0;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const OffSample& o = d_.off[idx[k]];
    if (n > 0 && o.i == off_kept_[n - 1].i && o.j == off_kept_[n - 1].j) continue;
    if (off_kept_.size() <= n) off_kept_.resize(n + 1), off_kept_owner_.resize(n + 1), off_kept_u_.resize(n + 1);
    off_kept_[n] = o;
    if (trace_) off_kept_owner_[n] = d_.off_owner[idx[k]], off_kept_u_[n] = d_.off_u[idx[k]];
    ++n;
  }
  d_.off.assign(off_kept_.begin(), off_kept_.begin() + std::ptrdiff_t(n));
  if (trace_) {
    d_.off_owner.assign(off_kept_owner_.begin(), off_kept_owner_.begin() + std::ptrdiff_t(n));
    d_.off_u.assign(off_kept_u_.begin(), off_kept_u_.begin() + std::ptrdiff_t(n));
  }
}

void Rasteriser::clear() {
  const int cols = d_.grid.cols;
  for (int i = d_.row0; i <= d_.row1; ++i) {
    if (d_.span0[i] <= d_.span1[i])
      std::fill(&d_.z[std::size_t(i) * cols + d_.span0[i]], &d_.z[std::size_t(i) * cols + d_.span1[i]] + 1, kInf);
    d_.span0[i] = cols, d_.span1[i] = -1;
  }
  d_.row0 = d_.grid.rows, d_.row1 = -1;
  d_.zlo = kInf;
  d_.off.clear();
  d_.off_u.clear();
  d_.off_owner.clear();
}

}  // namespace ptnet::detail
