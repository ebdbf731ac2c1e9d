// Retargeting: target bone lengths on every frame, bone directions kept,
// feet re-grounded, root displacement scaled by leg length, taller bodies
// take longer strides; also on the shared real mocap clips when present.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "motion/motion_internal.hpp"
#include "motion_gait_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {
namespace {

Motion walk(int performer = 1, double seconds = 12) {
  GenerateOptions o;
  o.performer = performer;
  o.seconds = seconds;
  return generate_motion(o);
}

double leg(const Pose& p) { return (p[kLeftKnee] - p[kLeftHip]).norm() + (p[kLeftAnkle] - p[kLeftKnee]).norm(); }

double percentile_lowest(const Motion& m, double q) {
  std::vector<double> z;
  for (const Pose& p : m.frames) z.push_back(lowest_foot_z(p));
  std::sort(z.begin(), z.end());
  return z[std::size_t(q * (z.size() - 1))];
}

// Mean distance between successive contacts of the same foot (m).
double mean_stride(const Motion& m) {
  const auto contacts = testing::foot_contacts(m);
  double sum = 0;
  int n = 0;
  for (int side = 0; side < 2; ++side) {
    Eigen::Vector2d prev(1e9, 1e9);
    for (const auto& c : contacts) {
      if (c.side != side) continue;
      const Eigen::Vector2d at = testing::sole_points(m.frames[c.first + (c.last - c.first) / 2], side).heel.head<2>();
      if (prev.x() < 1e8) {
        sum += (at - prev).norm();
        ++n;
      }
      prev = at;
    }
  }
  return n ? sum / n : 0;
}

void expect_canonical_lengths(const Motion& m, double height_cm) {
  const Pose o = canonical_rest_offsets(height_cm);
  for (const Pose& p : m.frames)
    for (int j = 1; j < kJointCount; ++j)
      ASSERT_NEAR((p[j] - p[joint_parent(j)]).norm(), o[j].norm(), 1e-9) << joint_name(j);
}

TEST(Retarget, BoneLengthsAreTheTargetsOnEveryFrame) {
  const Motion src = walk();
  for (double h : {150.0, 172.0, 198.0}) expect_canonical_lengths(retarget(src, h), h);
}

TEST(Retarget, BoneDirectionsAreKept) {
  const Motion src = walk();
  const Motion dst = retarget(src, 155);
  for (int f = 0; f < src.size(); ++f)
    for (int j : {kChest, kHead, kLeftKnee, kLeftAnkle, kLeftToe, kRightKnee, kRightToe, kLeftElbow, kRightWrist}) {
      const int p = joint_parent(j);
      const Eigen::Vector3d a = (src.frames[f][j] - src.frames[f][p]).normalized();
      const Eigen::Vector3d b = (dst.frames[f][j] - dst.frames[f][p]).normalized();
      ASSERT_GT(a.dot(b), 1 - 1e-9) << joint_name(j);
    }
}

TEST(Retarget, OntoItsOwnHeightChangesNothing) {
  const Motion src = walk(2);
  const Motion dst = retarget(src, performer_height_cm(2));
  for (int f = 0; f < src.size(); ++f)
    for (int j = 0; j < kJointCount; ++j) ASSERT_LT((src.frames[f][j] - dst.frames[f][j]).norm(), 1e-6);
}

TEST(Retarget, FeetAreGroundedDuringStance) {
  const Motion src = walk();
  for (double h : {150.0, 198.0}) {
    const Motion dst = retarget(src, h);
    EXPECT_NEAR(percentile_lowest(dst, 0.05), 0.0, 1e-12);
    for (const Pose& p : dst.frames) EXPECT_GT(lowest_foot_z(p), -0.02);
    const auto contacts = testing::foot_contacts(dst);
    ASSERT_GE(contacts.size(), 10u);
    for (const auto& c : contacts) {
      EXPECT_LT(std::abs(c.min_z), 0.02);
      EXPECT_LT(c.heel_slip, 0.02);
    }
  }
}

TEST(Retarget, RootDisplacementScalesWithLegLength) {
  const Motion src = walk();
  const Motion dst = retarget(src, 160);
  const double ratio = leg(dst.frames[0]) / leg(src.frames[0]);
  for (int f = 0; f < src.size(); ++f) {
    const Eigen::Vector2d a = src.frames[f][kPelvis].head<2>() - src.frames[0][kPelvis].head<2>();
    const Eigen::Vector2d b = dst.frames[f][kPelvis].head<2>() - dst.frames[0][kPelvis].head<2>();
    ASSERT_LT((b - ratio * a).norm(), 1e-9);
  }
  EXPECT_EQ(dst.frames[0][kPelvis].head<2>(), src.frames[0][kPelvis].head<2>());
}

TEST(Retarget, TallerBodiesTakeLongerStrides) {
  const Motion src = walk(3);
  const double short_stride = mean_stride(retarget(src, 155));
  const double tall_stride = mean_stride(retarget(src, 195));
  EXPECT_GT(short_stride, 0.4);
  EXPECT_NEAR(tall_stride / short_stride, 195.0 / 155.0, 0.05);
}

TEST(Retarget, RejectsImpossibleTargets) {
  const Motion src = walk(1, 1);
  EXPECT_THROW(retarget(src, 0), Error);
  EXPECT_THROW(retarget(src, 400), Error);
  EXPECT_THROW(retarget(Motion{}, 170), Error);
}

TEST(Retarget, RealMocapClipsTakeTheTargetSkeletonAndStayGrounded) {
  const std::filesystem::path dir = PTNET_SHARED_MOCAP;
  if (!std::filesystem::exists(dir / "clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  int done = 0;
  for (const char* name : {"002_01.bvh", "141_15.bvh"}) {
    if (!std::filesystem::exists(dir / name)) continue;
    const Motion src = load_motion((dir / name).string(), MotionOptions{});
    for (double h : {152.0, 191.0}) {
      const Motion dst = retarget(src, h);
      expect_canonical_lengths(dst, h);
      EXPECT_NEAR(percentile_lowest(dst, 0.05), 0.0, 1e-12) << name;
      EXPECT_NEAR(standing_height(dst), h / 100, 0.1 * h / 100) << name;
      // Retargeted real motion is on the canonical skeleton (rigid pelvis and
      // chest groups), so the canonical BVH reproduces it exactly.
      const Bvh bvh = motion_to_bvh(dst);
      const auto world = forward_kinematics(parse_bvh(format_bvh(bvh), "rt.bvh"), 0.01, UpAxis::y);
      double err = 0;
      for (int f = 0; f < dst.size(); ++f)
        for (int j = 0; j < kJointCount; ++j)
          err = std::max(err, (world[std::size_t(f) * kJointCount + bvh.find(joint_name(j))] - dst.frames[f][j]).norm());
      EXPECT_LT(err, 1e-4) << name;
    }
    ++done;
  }
  EXPECT_GT(done, 0);
}

}  // namespace
}  // namespace ptnet
