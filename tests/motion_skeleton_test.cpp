// The canonical skeleton: rest offsets as in the team notes (Drillis-Contini
// fractions of H), and the rest pose built from them stands on the floor and
// measures H.
#include <gtest/gtest.h>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {
namespace {

void expect_offset(const Pose& o, int j, double x, double y, double z, double h) {
  EXPECT_NEAR(o[j].x(), x * h, 1e-4 * h) << joint_name(j);
  EXPECT_NEAR(o[j].y(), y * h, 1e-4 * h) << joint_name(j);
  EXPECT_NEAR(o[j].z(), z * h, 1e-4 * h) << joint_name(j);
}

TEST(Skeleton, RestOffsetsAreTheTeamSkeleton) {
  for (double height_cm : {150.0, 170.0, 193.5}) {
    const double h = height_cm / 100;
    const Pose o = canonical_rest_offsets(height_cm);
    expect_offset(o, kPelvis, 0, 0, 0.530, h);
    expect_offset(o, kSpine, 0, 0, 0.070, h);
    expect_offset(o, kChest, 0, 0, 0.120, h);
    expect_offset(o, kNeck, 0, 0, 0.098, h);
    expect_offset(o, kHead, 0, 0, 0.052, h);
    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? 1 : -1;
      const int hip = side == 0 ? kLeftHip : kRightHip, sh = side == 0 ? kLeftShoulder : kRightShoulder;
      expect_offset(o, hip, 0, s * 0.0475, 0, h);
      expect_offset(o, hip + 1, 0, 0, -0.245, h);
      expect_offset(o, hip + 2, 0, 0, -0.246, h);
      expect_offset(o, hip + 3, 0.0790, 0, -0.030, h);
      expect_offset(o, sh, 0, s * 0.1295, 0.098, h);
      expect_offset(o, sh + 1, 0, 0, -0.186, h);
      expect_offset(o, sh + 2, 0, 0, -0.146, h);
    }
  }
}

TEST(Skeleton, RestPoseStandsOnTheFloorAndMeasuresItsHeight) {
  const double h = 1.76;
  const Pose o = canonical_rest_offsets(h * 100);
  Pose p;
  p[kPelvis] = o[kPelvis];
  for (int j = 1; j < kJointCount; ++j) p[j] = p[joint_parent(j)] + o[j];
  EXPECT_NEAR(p[kLeftAnkle].z(), 0.039 * h, 1e-12);
  EXPECT_NEAR(p[kLeftKnee].z(), 0.285 * h, 1e-12);
  EXPECT_NEAR(p[kChest].z(), 0.720 * h, 1e-12);
  EXPECT_NEAR(p[kLeftShoulder].z(), 0.818 * h, 1e-12);
  EXPECT_NEAR(p[kHead].z(), 0.870 * h, 1e-12);
  EXPECT_NEAR(p[kLeftWrist].z(), 0.486 * h, 1e-12);  // Drillis-Contini wrist 0.485 H
  EXPECT_NEAR(lowest_foot_z(p), 0.0, 1e-12);
  Motion m;
  m.frames.assign(3, p);
  EXPECT_NEAR(standing_height(m), h, 1e-9);
}

TEST(Skeleton, RejectsANonPositiveHeight) {
  EXPECT_THROW(canonical_rest_offsets(0), Error);
  EXPECT_THROW(canonical_rest_offsets(-170), Error);
}

}  // namespace
}  // namespace ptnet
