// Simulator physics (issue 3): force balance in quiet standing, heavier body
// presses harder, taller body leaves longer footprints, left foot on the
// documented left side, determinism.
#include <gtest/gtest.h>

#include <cstring>

#include "core/anthropometry.hpp"
#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "sim_poses.hpp"

namespace ptnet {
namespace {

using test::rest_pose;
using test::still_motion;

double total_force_n(const PressureSequence& s, int t) {
  double sum = 0;
  for (int i = 0; i < s.mat.cells(); ++i) sum += s.frame(t)[i];
  return sum * 1000.0 * s.mat.cell_area_m2();  // kPa -> Pa
}

struct Footprint {
  int cells = 0, row_min = 1 << 30, row_max = -1;
  float peak = 0;
};
Footprint footprint(const PressureSequence& s, int t, int col_begin, int col_end) {
  Footprint f;
  for (int r = 0; r < s.mat.rows; ++r)
    for (int c = col_begin; c < col_end; ++c)
      if (s.at(t, r, c) > 0) {
        ++f.cells;
        f.row_min = std::min(f.row_min, r);
        f.row_max = std::max(f.row_max, r);
        f.peak = std::max(f.peak, s.at(t, r, c));
      }
  return f;
}

PressureSequence stand(double height_cm, double weight_kg, bool ideal = true, std::uint64_t seed = 1) {
  const Body body(BodySpec{"b", Sex::male, height_cm, weight_kg, "retargeted"});
  SimOptions o;
  if (ideal) o.sensor = ideal_sensor();
  o.seed = seed;
  return simulate(still_motion(rest_pose(height_cm), 30), body, o);
}

TEST(SimPhysics, QuietStandingForceEqualsWeight) {
  for (double w : {50.0, 75.0, 110.0}) {
    const PressureSequence s = stand(175, w);
    const double f = total_force_n(s, 15);
    EXPECT_NEAR(f, w * anthropometry::kGravity, 0.03 * w * anthropometry::kGravity) << w << " kg";
  }
}

TEST(SimPhysics, HeavierBodyPressesHarder) {
  const PressureSequence a = stand(175, 70), b = stand(175, 84);
  const double ratio = total_force_n(b, 15) / total_force_n(a, 15);
  EXPECT_NEAR(ratio, 1.2, 0.03);
  const Footprint fa = footprint(a, 15, 0, a.mat.cols), fb = footprint(b, 15, 0, b.mat.cols);
  EXPECT_GE(fb.cells, fa.cells);
  EXPECT_GT(fb.peak, fa.peak);
}

TEST(SimPhysics, TallerBodyLeavesLongerFootprints) {
  const PressureSequence a = stand(155, 70), b = stand(195, 70);
  const Footprint fa = footprint(a, 15, 0, a.mat.cols / 2), fb = footprint(b, 15, 0, b.mat.cols / 2);
  const double la = (fa.row_max - fa.row_min + 1) * a.mat.pitch_m;
  const double lb = (fb.row_max - fb.row_min + 1) * b.mat.pitch_m;
  EXPECT_GT(lb, la);
  // Footprint length follows foot length 0.152 H within a cell or two.
  EXPECT_NEAR(lb, 0.152 * 1.95, 0.05);
}

TEST(SimPhysics, BothFeetOnTheirDocumentedSides) {
  const PressureSequence s = stand(175, 70);
  const Footprint left = footprint(s, 15, 0, s.mat.cols / 2);
  const Footprint right = footprint(s, 15, s.mat.cols / 2, s.mat.cols);
  EXPECT_GT(left.cells, 10);
  EXPECT_GT(right.cells, 10);
}

TEST(SimPhysics, LeftFootOnlyStanceLightsTheLeftColumns) {
  Pose p = rest_pose(175);
  test::move_leg(p, /*left=*/false, Eigen::Vector3d(0, 0, 0.10));  // lift the right foot
  const Body body(BodySpec{"b", Sex::male, 175, 70, "retargeted"});
  SimOptions o;
  o.sensor = ideal_sensor();
  const PressureSequence s = simulate(still_motion(p, 30), body, o);
  const Footprint left = footprint(s, 15, 0, s.mat.cols / 2);
  const Footprint right = footprint(s, 15, s.mat.cols / 2, s.mat.cols);
  EXPECT_GT(left.cells, 10);
  EXPECT_EQ(right.cells, 0);
  EXPECT_NEAR(total_force_n(s, 15), 70 * anthropometry::kGravity, 0.03 * 70 * anthropometry::kGravity);
}

TEST(SimPhysics, SameSeedSameBytesOtherSeedOnlyNoise) {
  const PressureSequence a = stand(175, 70, false, 7), b = stand(175, 70, false, 7);
  EXPECT_EQ(a.kpa, b.kpa);
  const PressureSequence c = stand(175, 70, false, 8);
  EXPECT_NE(a.kpa, c.kpa);
  EXPECT_NEAR(total_force_n(a, 15), total_force_n(c, 15), 0.03 * 70 * anthropometry::kGravity);
}

}  // namespace
}  // namespace ptnet
