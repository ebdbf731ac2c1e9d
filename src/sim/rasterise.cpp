// Depth from below: the lowest body surface over S x S samples per mat cell,
// and each cell's mean penetration into the compliance band.
//
// Surfaces: the sole patches (a plane plus the soft-tissue height table of
// ptnet::SoleSurface, sampled analytically per sample) and the lower surfaces
// of the segment capsules (a chain of spheres along each tapered capsule,
// spaced at a third of the smaller radius: the envelope sags < r / 70).
// Only the samples under each surface's bounding box are visited, and only
// surfaces whose lowest point is within the band are rasterised.
#include <algorithm>
#include <cmath>
#include <limits>

#include "sim_internal.hpp"

namespace ptnet::detail {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
}

Rasteriser::Rasteriser(const MatSpec& mat, int subsamples, double compliance_m)
    : mat_(mat),
      s_(subsamples),
      band_(float(compliance_m)),
      ds_(mat.pitch_m / subsamples),
      half_l_(0.5 * mat.rows * mat.pitch_m),
      half_w_(0.5 * mat.cols * mat.pitch_m),
      ns_rows_(mat.rows * subsamples),
      ns_cols_(mat.cols * subsamples),
      zbuf_(std::size_t(ns_rows_) * ns_cols_, kInf) {
  di0_ = ns_rows_, di1_ = -1, dj0_ = ns_cols_, dj1_ = -1;
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
  di0_ = std::min(di0_, std::max(i0, 0));
  di1_ = std::max(di1_, std::min(i1, ns_rows_ - 1));
  dj0_ = std::min(dj0_, std::max(j0, 0));
  dj1_ = std::max(dj1_, std::min(j1, ns_cols_ - 1));
}

void Rasteriser::patch(const SoleSurface& sole, const SolePatch& p) {
  const Eigen::Vector3d& n = p.up;
  if (n.z() < 0.2) return;  // sole nearly vertical: its edge is not modelled
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
  if (zmin > band_) return;
  int i0, i1, j0, j1;
  row_range(x0, x1, i0, i1);
  col_range(y0, y1, j0, j1);
  if (i0 > i1 || j0 > j1) return;
  touch(i0, i1, j0, j1);

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
  const float* table = sole.height_m.data();
  const int nu = sole.nu, nv = sole.nv;
  for (int i = i0; i <= i1; ++i) {
    const double dX = half_l_ - (i + 0.5) * ds_ - ox;
    for (int j = j0; j <= j1; ++j) {
      const double dY = half_w_ - (j + 0.5) * ds_ - oy;
      const double fi = fi0 + iu * (sx * dX + sy * dY);
      if (fi < fi_lo || fi >= fi_hi) continue;
      const double fj = fj0 + iv * (wx * dX + wy * dY);
      const int ti = int(fi + 0.5), tj = int(fj + 0.5);
      if (ti < 0 || ti >= nu || fj < -0.5 || tj >= nv) continue;
      const float h = table[std::size_t(ti) * nv + tj];
      if (h >= SoleSurface::kOutside) continue;
      record(i, j, float(oz + zx * dX + zy * dY) + h * inv_nz);
    }
  }
}

void Rasteriser::sphere(double cx, double cy, double cz, double r) {
  if (cz - r > band_) return;
  int i0, i1, j0, j1;
  row_range(cx - r, cx + r, i0, i1);
  col_range(cy - r, cy + r, j0, j1);
  if (i0 > i1 || j0 > j1) return;
  touch(i0, i1, j0, j1);
  const double r2 = r * r;
  for (int i = i0; i <= i1; ++i) {
    const double dx = half_l_ - (i + 0.5) * ds_ - cx;
    for (int j = j0; j <= j1; ++j) {
      const double dy = half_w_ - (j + 0.5) * ds_ - cy;
      const double d2 = dx * dx + dy * dy;
      if (d2 < r2) record(i, j, float(cz - std::sqrt(r2 - d2)));
    }
  }
}

void Rasteriser::capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra, double rb) {
  if (std::min(a.z() - ra, b.z() - rb) > band_) return;
  const double len = (b - a).norm();
  const int n = 1 + int(std::ceil(len / (std::min(ra, rb) / 3)));
  for (int k = 0; k <= n; ++k) {
    const double t = double(k) / n;
    const Eigen::Vector3d c = a + t * (b - a);
    sphere(c.x(), c.y(), c.z(), ra + t * (rb - ra));
  }
}

double Rasteriser::penetration(const Body& body, const PosedBody& posed, float* pen) {
  off_pen_ = 0;
  for (const auto& p : posed.left_foot) patch(body.sole(), p);
  for (const auto& p : posed.right_foot) patch(body.sole(), p);
  const auto& segs = body.segments();
  for (int s = 0; s < kSegmentCount; ++s)
    if (segs[s].touches_ground) capsule(posed.a[s], posed.b[s], segs[s].radius_a_m, segs[s].radius_b_m);

  std::fill(pen, pen + mat_.cells(), 0.0f);
  const float inv_s2 = 1.0f / float(s_ * s_);
  double total = off_pen_ * inv_s2;
  if (di1_ >= di0_ && dj1_ >= dj0_) {
    // Whole cells covering the dirty rectangle.
    const int r0 = di0_ / s_, r1 = di1_ / s_, c0 = dj0_ / s_, c1 = dj1_ / s_;
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        float sum = 0;
        for (int a = 0; a < s_; ++a) {
          float* z = &zbuf_[std::size_t(r * s_ + a) * ns_cols_ + c * s_];
          for (int b = 0; b < s_; ++b) {
            if (z[b] < band_) sum += band_ - z[b];
            z[b] = kInf;
          }
        }
        pen[r * mat_.cols + c] = sum * inv_s2;
        total += sum * inv_s2;
      }
    }
  }
  di0_ = ns_rows_, di1_ = -1, dj0_ = ns_cols_, dj1_ = -1;
  return total;
}

}  // namespace ptnet::detail
