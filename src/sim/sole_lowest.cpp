// The lowest point of a posed sole patch: the reference scan of its whole
// height table (patch_lowest_z(sole, patch)) and the same value found by
// scanning only the table rows that can hold it (SoleRows).
//
// Dimension legend: nu x nv the sole's height table (rows along the foot, u;
// columns across it, v).
#include <algorithm>
#include <cmath>
#include <limits>

#include "sim_internal.hpp"

namespace ptnet::detail {
namespace {

// The sole coordinate u of table row i, and v of column j.
double row_u(const SoleSurface& sole, int i) { return double(i) / (sole.nu - 1); }
double col_v(const SoleSurface& sole, int j) {
  return sole.v_min + (sole.v_max - sole.v_min) * j / (sole.nv - 1);
}

// The height of the patch's plane at row u (m), before the sideways and
// the table's terms.
double along_z(const SoleSurface& sole, const SolePatch& p, double u) {
  return p.origin.z() + p.forward.z() * ((u - p.u_origin) * sole.length_m);
}

// `lowest` lowered to each foot cell of columns [j0, j1] of row i, in
// column order (the reference's operations, in its order).
void scan_row(const SoleSurface& sole, const SolePatch& p, int i, int j0, int j1, double& lowest) {
  const double along = along_z(sole, p, row_u(sole, i));
  for (int j = j0; j <= j1; ++j) {
    const float h = sole.height_m[std::size_t(i) * std::size_t(sole.nv) + std::size_t(j)];
    if (!(h < SoleSurface::kOutside)) continue;
    const double v = col_v(sole, j);
    lowest =
        std::min(lowest, along + p.left.z() * (p.medial_sign * v * sole.width_m) + p.up.z() * h);
  }
}

bool patch_row(const SolePatch& p, double u) { return !(u < p.u_begin || u > p.u_end); }

}  // namespace

double patch_lowest_z(const SoleSurface& sole, const SolePatch& p) {
  double lowest = 1e300;
  for (int i = 0; i < sole.nu; ++i)
    if (patch_row(p, row_u(sole, i))) scan_row(sole, p, i, 0, sole.nv - 1, lowest);
  return lowest;
}

double foot_lowest_z(const SoleSurface& sole, const std::array<SolePatch, 2>& foot) {
  return std::min(patch_lowest_z(sole, foot[0]), patch_lowest_z(sole, foot[1]));
}

SoleRows::SoleRows(const SoleSurface& sole)
    : first(std::size_t(std::max(sole.nu, 0)), sole.nv),
      last(std::size_t(std::max(sole.nu, 0)), -1),
      h_lo(first.size(), std::numeric_limits<double>::infinity()),
      h_hi(first.size(), -std::numeric_limits<double>::infinity()),
      v_first(first.size(), 0.0),
      v_last(first.size(), 0.0),
      u(first.size(), 0.0) {
  for (int i = 0; i < sole.nu; ++i) {
    u[std::size_t(i)] = row_u(sole, i);
    for (int j = 0; j < sole.nv; ++j) {
      const float h = sole.height_m[std::size_t(i) * std::size_t(sole.nv) + std::size_t(j)];
      if (!(h < SoleSurface::kOutside)) continue;
      first[std::size_t(i)] = std::min(first[std::size_t(i)], j), last[std::size_t(i)] = j;
      h_lo[std::size_t(i)] = std::min(h_lo[std::size_t(i)], double(h));
      h_hi[std::size_t(i)] = std::max(h_hi[std::size_t(i)], double(h));
      h_abs = std::max(h_abs, std::abs(double(h)));
      h_min = std::min(h_min, double(h)), h_max = std::max(h_max, double(h));
      v_first[std::size_t(i)] = col_v(sole, first[std::size_t(i)]);
      v_last[std::size_t(i)] = col_v(sole, j);
    }
  }
}

namespace {

bool has_cells(const SoleRows& rows, int i) {
  return rows.first[std::size_t(i)] <= rows.last[std::size_t(i)];
}

// A lower bound (m) of every value scan_row computes on row i (which holds
// foot cells), short of the rounding of either by at most `slack`.
double row_bound(const SoleSurface& sole, const SoleRows& rows, const SolePatch& p, int i) {
  const std::size_t r = std::size_t(i);
  const double side = p.left.z() * p.medial_sign * sole.width_m, up = p.up.z();
  return along_z(sole, p, rows.u[r]) + std::min(side * rows.v_first[r], side * rows.v_last[r]) +
         std::min(up * rows.h_lo[r], up * rows.h_hi[r]);
}

// A bound of the magnitudes the values of patch p add up (m): the
// rounding of a value, or of a row's bound, is a few ulps of it. Not
// finite when the patch is not.
double bound_scale(const SoleSurface& sole, const SoleRows& rows, const SolePatch& p) {
  const double side =
      std::abs(p.left.z() * sole.width_m) * std::max(std::abs(sole.v_min), std::abs(sole.v_max));
  return 1 + std::abs(p.origin.z()) +
         std::abs(p.forward.z()) * sole.length_m * (1 + std::abs(p.u_origin)) + side +
         std::abs(p.up.z()) * rows.h_abs;
}

// A lower bound (m) of every row_bound of patch p: its terms' lowest over
// the patch's rows (along is linear in u), any column and any height.
double patch_bound(const SoleSurface& sole, const SoleRows& rows, const SolePatch& p) {
  const double u0 = std::max(0.0, p.u_begin), u1 = std::min(1.0, p.u_end);
  const double side = p.left.z() * p.medial_sign * sole.width_m, up = p.up.z();
  return std::min(along_z(sole, p, u0), along_z(sole, p, u1)) +
         std::min(side * sole.v_min, side * sole.v_max) +
         std::min(up * rows.h_min, up * rows.h_max);
}

// The row of patch p with foot cells and the lowest bound (-1: none).
int lowest_bound_row(const SoleSurface& sole, const SoleRows& rows, const SolePatch& p) {
  int seed = -1;
  double lowest = 0;
  for (int i = 0; i < sole.nu; ++i)
    if (has_cells(rows, i) && patch_row(p, rows.u[std::size_t(i)])) {
      const double b = row_bound(sole, rows, p, i);
      if (seed < 0 || b < lowest) seed = i, lowest = b;
    }
  return seed;
}

}  // namespace

// Every value is a linear function of the cell's (u, v, h) plus rounding;
// a row whose bound lies above a value already found (by more than all the
// rounding there is) holds no lower value, nor an equal one. The rows left
// are scanned in the reference's order, so the result is its value, bit for
// bit (the first of equal values, as the reference keeps).
double patch_lowest_z(const SoleSurface& sole, const SoleRows& rows, const SolePatch& p) {
  const double slack = 1e-12 * bound_scale(sole, rows, p);
  if (!std::isfinite(slack) || int(rows.first.size()) != sole.nu) return patch_lowest_z(sole, p);
  // A value to prune against: the lowest of the row with the lowest bound.
  const int seed = lowest_bound_row(sole, rows, p);
  if (seed < 0) return 1e300;
  double cut = 1e300;
  scan_row(sole, p, seed, rows.first[std::size_t(seed)], rows.last[std::size_t(seed)], cut);
  double lowest = 1e300;
  for (int i = 0; i < sole.nu; ++i)
    if (has_cells(rows, i) && patch_row(p, rows.u[std::size_t(i)]) &&
        !(row_bound(sole, rows, p, i) - slack > std::min(cut, lowest)))
      scan_row(sole, p, i, rows.first[std::size_t(i)], rows.last[std::size_t(i)], lowest);
  return lowest;
}

double foot_lowest_z(const SoleSurface& sole, const SoleRows& rows,
                     const std::array<SolePatch, 2>& foot) {
  return std::min(patch_lowest_z(sole, rows, foot[0]), patch_lowest_z(sole, rows, foot[1]));
}

namespace {

// Whether fl(v - floor) < band for a value v of row i (a foot cell), in
// the reference's order.
bool row_below(const SoleSurface& sole, const SolePatch& p, int i, int j0, int j1, double floor,
               double band) {
  const double along = along_z(sole, p, row_u(sole, i));
  for (int j = j0; j <= j1; ++j) {
    const float h = sole.height_m[std::size_t(i) * std::size_t(sole.nv) + std::size_t(j)];
    if (!(h < SoleSurface::kOutside)) continue;
    const double v = col_v(sole, j);
    if (along + p.left.z() * (p.medial_sign * v * sole.width_m) + p.up.z() * h - floor < band)
      return true;
  }
  return false;
}

// Whether patch_lowest_z(sole, p) - floor < band: whether some cell's value
// v has fl(v - floor) < band (subtracting is monotone: the lowest value
// passes exactly when some value does). Rows whose bound, less the
// rounding, already fails are not scanned, nor any row when the patch's
// bound fails; the first cell that passes ends the scan.
bool patch_below(const SoleSurface& sole, const SoleRows& rows, const SolePatch& p, double floor,
                 double band) {
  const double slack = 1e-12 * bound_scale(sole, rows, p);
  if (!std::isfinite(slack + floor + band) || int(rows.first.size()) != sole.nu)
    return patch_lowest_z(sole, p) - floor < band;
  const auto passes = [&](int i) { return !(row_bound(sole, rows, p, i) - slack - floor >= band); };
  const auto scan = [&](int i) {
    return row_below(sole, p, i, rows.first[std::size_t(i)], rows.last[std::size_t(i)], floor,
                     band);
  };
  if (!(patch_bound(sole, rows, p) - slack - floor < band)) return false;  // no row can pass
  for (int i = 0; i < sole.nu; ++i)
    if (has_cells(rows, i) && patch_row(p, rows.u[std::size_t(i)]) && passes(i) && scan(i))
      return true;
  return false;
}

}  // namespace

bool foot_below(const SoleSurface& sole, const SoleRows& rows, const std::array<SolePatch, 2>& foot,
                double floor, double band) {
  return patch_below(sole, rows, foot[0], floor, band) ||
         patch_below(sole, rows, foot[1], floor, band);
}

}  // namespace ptnet::detail
