// Internal pieces of the simulator (see ptnet/sim.hpp).
//
// Dimension legend: T frames, R x C mat cells, S x S samples per cell.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/sim.hpp"

namespace ptnet::detail {

// Where the mat lies under a sequence: world -> mat coordinates per frame,
// X = axis . (p - centre) (towards row 0), Y = left . (p - centre) (towards col 0).
struct MatPlacement {
  Eigen::Vector2d axis{1, 0}, left{0, 1};
  std::vector<Eigen::Vector2d> centre;  // [T] (all equal for Placement::fixed)
};
MatPlacement place_on_mat(const Motion& motion, const SimOptions& options);

// Gaussian smoothing of a series with sigma in samples, edges renormalised.
std::vector<double> gaussian_smooth(const std::vector<double>& x, double sigma);

// Depth-from-below rasteriser over the S x S sample grid of the mat. Reused
// across frames: no allocation after construction.
class Rasteriser {
 public:
  Rasteriser(const MatSpec& mat, int subsamples, double compliance_m);

  // Rasterises one posed body (mat coordinates) and writes each cell's mean
  // penetration (m) into pen[R * C]; returns the total penetration of all
  // contact, on and off the mat, in the same units (sum over cells).
  double penetration(const Body& body, const PosedBody& posed, float* pen);

 private:
  void patch(const SoleSurface& sole, const SolePatch& p);
  void capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra, double rb);
  void sphere(double cx, double cy, double cz, double r);
  // Sample index range [lo, hi] covering mat coordinate range [x0, x1] along rows/cols.
  void row_range(double x0, double x1, int& lo, int& hi) const;
  void col_range(double y0, double y1, int& lo, int& hi) const;
  void touch(int i0, int i1, int j0, int j1);
  // Records depth z at sample (i, j) (which may lie off the mat).
  void record(int i, int j, float z) {
    if (i >= 0 && i < ns_rows_ && j >= 0 && j < ns_cols_) {
      float& d = zbuf_[std::size_t(i) * ns_cols_ + j];
      if (z < d) d = z;
    } else if (z < band_) {
      off_pen_ += band_ - z;
    }
  }

  MatSpec mat_;
  int s_;
  float band_;
  double ds_, half_l_, half_w_;
  int ns_rows_, ns_cols_;
  std::vector<float> zbuf_;  // [R S, C S] lowest surface height (m), +inf: none
  int di0_, di1_, dj0_, dj1_;  // dirty sample rectangle
  double off_pen_ = 0;
};

// Applies the sensor model to one frame in place: [R * C] kPa. `scratch` has
// R * C floats; `rng` is the frame's noise stream state.
void apply_sensor(const SensorModel& sensor, const MatSpec& mat, float* frame, float* scratch,
                  std::uint64_t& rng);

}  // namespace ptnet::detail
