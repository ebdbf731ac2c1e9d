// The simulator's depth from below and elastic foundation written plainly,
// for the tests that hold the fast path (src/sim: detail::Rasteriser) to it
// (tests/sim_reference_test.cpp). Every candidate sample is tested on its
// own, in double, and kept in a map; the sink level is solved exactly, on
// the sorted heights; the steps follow ptnet/sim.hpp's description.
//
// Dimension legend: R x C mat cells of pitch p, S x S samples per cell
// (sample pitch ds = p / S); sample (i, j) has its centre at X = R p / 2 -
// (i + 0.5) ds, Y = C p / 2 - (j + 0.5) ds (mat coordinates, m), on the mat
// when 0 <= i < R S and 0 <= j < C S.
//
// It shares the fast path's surface model, which is the model and not a
// shortcut:
//  - a sole patch (SolePatch) covers the samples whose centre lies within
//    the axis-aligned box of its four corners (u_begin, u_end x v_min, v_max
//    on its plane), when its lowest corner is below the reach (compliance +
//    max sink) and its up.z >= 0.2; a sample's height is the plane's under
//    its centre plus the height of the nearest cell of the sole's table
//    over up.z, when that cell's row is within half a row of [u_begin,
//    u_end] and it is foot (< SoleSurface::kOutside);
//  - a capsule is a chain of n + 1 spheres, n = 1 + ceil(length / (min
//    radius / 3)), radii linear along it; a sphere's height at a sample
//    within its radius is its lower surface, cz - sqrt(r^2 - d^2);
//  - heights at or above the reach are not recorded; a sample holds the
//    lowest (on ties the first: left sole, right sole, capsules in segment
//    order), off the mat as on it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/sim.hpp"

namespace ptnet::test {

// One recorded sample: indices (i, j) (off the mat: outside [0, R S) x [0,
// C S)), lowest surface height z (m), owner 1 left sole, 2 right sole, 3
// other, and the sole coordinate u (0 heel .. 1 toe tip; 0 for other).
struct RefSample {
  int i = 0, j = 0;
  float z = 0;
  int owner = 0;
  float u = 0;
};

// The samples of `posed` (mat coordinates, m) under options.mat,
// options.subsamples, options.compliance_m and options.max_sink_m.
std::vector<RefSample> reference_depth(const Body& body, const PosedBody& posed,
                                       const SimOptions& options);

// The sink level s (m): sum over samples of max(0, s - z) = load_n / (k
// ds^2), k = options.stiffness_kpa_per_mm (in Pa per m), at most
// options.max_sink_m above the lowest sample (that bound added in float, as
// the simulator adds it); solved on the sorted heights, exact up to double
// rounding. The lowest height when there are no samples.
double reference_sink_level(const std::vector<RefSample>& samples, double load_n,
                            const SimOptions& options);

struct ReferenceFrame {
  std::vector<double> kpa;     // [R * C] pressure, kPa
  FrameTrace trace;            // as simulate()'s
  double scale = 0;            // kPa per m of weighted penetration (0: nothing carried)
  Eigen::Vector2d tilt{0, 0};  // g, per m
  // What the tests' error bounds read, over the contact cells (and samples
  // off the mat): the largest mean penetration (m), weight and Mahalanobis
  // distance from the centroid, and the sum of the penetrations over the sum
  // of the weighted ones.
  double max_penetration_m = 0, max_weight = 0, max_mahalanobis = 0, unweighted_ratio = 0;
};

// The foundation at sink level `level` (m) carrying load_n (N), tilted
// towards `target` (mat X, Y; m; null: no tilt):
//  1. contact: the lowest sample below options.compliance_m and a load > 0;
//  2. penetration: each mat cell's mean of max(0, level - z) over its
//     S x S samples; a sample off the mat is a cell of its own (its
//     penetration / S^2, at its centre);
//  3. tilt: the weights max(0, 1 + g . (r - c)), c the penetration
//     centroid, g = C^-1 d, C the penetration-weighted covariance of the
//     cells (plus p^2 / 12 on the diagonal: a cell's own extent), d the
//     target's offset from c shortened to 0.6 standard deviations
//     (Mahalanobis) when beyond;
//  4. load scaling: pressure = weighted penetration x scale, the scale such
//     that the pressures x cell area sum to load_n on and off the mat;
//  5. trace: each sample with penetration carries penetration x scale x
//     ds^2 x its cell's weight, summed per owner (heel: u < 0.3, forefoot:
//     u >= 0.6; cop_u the force-weighted mean u; area ds^2 per sample).
ReferenceFrame reference_distribute(const std::vector<RefSample>& samples, double level,
                                    double load_n, const Eigen::Vector2d* target,
                                    const SimOptions& options);

}  // namespace ptnet::test
