// Retargeting onto a body of a given height (canonical bone lengths).
//
// Joint rotations kept, up to bone twist: every bone keeps its world
// direction per frame and takes the target's length. The two rigid groups of
// the canonical skeleton, the pelvis (spine, hips) and the chest (neck,
// shoulders), are placed by the frame of their bones in the source (lateral
// axis from right to left joint, up axis towards spine / neck), since the
// canonical hip and shoulder offsets need not point the way the source rig's
// do. The root translation scales with leg length; the motion is re-grounded
// so that the lowest foot point during stance is at z = 0.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "rotation.hpp"

namespace ptnet {

using Eigen::Matrix3d;
using detail::frame_from;
using Eigen::Vector3d;

namespace {

constexpr double kGroundPercentile = 0.05;  // of per-frame lowest foot points: stance, robust to noise

double leg_length(const Pose& p) {
  double sum = 0;
  for (int hip : {kLeftHip, kRightHip})
    sum += (p[hip + 1] - p[hip]).norm() + (p[hip + 2] - p[hip + 1]).norm();
  return 0.5 * sum;
}

}  // namespace

double retarget_scale(const Motion& motion, double height_cm) {
  if (motion.frames.empty()) throw Error(motion.name + ": cannot retarget a motion with no frames");
  if (!(height_cm >= 50 && height_cm <= 250))
    throw Error(motion.name + ": expected a target height in [50, 250] cm, found " + number_text(height_cm));
  const Pose o = canonical_rest_offsets(height_cm);
  double source_leg = 0;
  for (const Pose& p : motion.frames) source_leg += leg_length(p);
  source_leg /= motion.size();
  if (!(source_leg > 1e-6)) throw Error(motion.name + ": source legs have zero length");
  return (o[kLeftKnee].norm() + o[kLeftAnkle].norm()) / source_leg;
}

Motion retarget(const Motion& motion, double height_cm) {
  const double ratio = retarget_scale(motion, height_cm);  // validates
  const Pose o = canonical_rest_offsets(height_cm);
  Vector3d origin = motion.frames.front()[kPelvis];
  origin.z() = 0;

  Motion out;
  out.name = motion.name;
  out.fps = motion.fps;
  out.start_s = motion.start_s;
  out.frames.reserve(motion.frames.size());
  std::vector<double> lowest;
  lowest.reserve(motion.frames.size());
  for (const Pose& p : motion.frames) {
    Pose q;
    q[kPelvis] = origin + ratio * (p[kPelvis] - origin);
    const Matrix3d r_pelvis = frame_from(p[kLeftHip] - p[kRightHip], p[kSpine] - p[kPelvis]);
    const Matrix3d r_chest = frame_from(p[kLeftShoulder] - p[kRightShoulder], p[kNeck] - p[kChest]);
    for (int j = 1; j < kJointCount; ++j) {
      const int parent = joint_parent(j);
      if (j == kSpine || j == kLeftHip || j == kRightHip) {
        q[j] = q[kPelvis] + r_pelvis * o[j];
      } else if (j == kNeck || j == kLeftShoulder || j == kRightShoulder) {
        q[j] = q[kChest] + r_chest * o[j];
      } else {
        const Vector3d bone = p[j] - p[parent];
        const Vector3d dir = bone.norm() > 1e-9 ? Vector3d(bone.normalized()) : Vector3d(o[j].normalized());
        q[j] = q[parent] + o[j].norm() * dir;
      }
    }
    lowest.push_back(lowest_foot_z(q));
    out.frames.push_back(q);
  }
  // Re-ground: a low percentile of the lowest foot point is the floor.
  std::vector<double> sorted = lowest;
  const std::size_t k = std::size_t(kGroundPercentile * double(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
  const double floor_z = sorted[k];
  for (Pose& q : out.frames)
    for (Vector3d& v : q) v.z() -= floor_z;
  return out;
}

}  // namespace ptnet
