// A Motion as a BVH on the canonical skeleton.
//
// Joint rotations are derived from the positions: the pelvis and the chest
// (several children) take the frame of their lateral and up bones; every
// other joint the shortest rotation, in its parent's frame, turning its rest
// bone onto the current one (swing only, no twist); end joints (head, toes,
// wrists) keep their parent's orientation. Converted to ZXY Euler angles in
// the BVH's y-up axes, centimetres.
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <numeric>

#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "rotation.hpp"
#include "rig.hpp"

namespace ptnet {

using Eigen::Matrix3d;
using detail::frame_from;
using Eigen::Vector3d;

namespace {

// Depth-first order (the order of a nested BVH file).
constexpr std::array<int, kJointCount> kFileOrder{
    kPelvis,     kSpine,        kChest,      kNeck,       kHead,           kLeftShoulder, kLeftElbow,
    kLeftWrist,  kRightShoulder, kRightElbow, kRightWrist, kLeftHip,        kLeftKnee,     kLeftAnkle,
    kLeftToe,    kRightHip,     kRightKnee,  kRightAnkle, kRightToe};

// world = kP * bvh: world x = bvh z, world y = bvh x, world z = bvh y.
Matrix3d bvh_to_world() {
  Matrix3d p;
  p << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  return p;
}

Vector3d to_bvh_cm(const Vector3d& world_m) { return 100.0 * (bvh_to_world().transpose() * world_m); }

// R = Rz(a) Rx(b) Ry(c); returns (a, b, c) in degrees.
Vector3d zxy_degrees(const Matrix3d& r) {
  const double b = std::asin(std::clamp(r(2, 1), -1.0, 1.0));
  double a, c;
  if (std::abs(r(2, 1)) < 1 - 1e-12) {
    a = std::atan2(-r(0, 1), r(1, 1));
    c = std::atan2(-r(2, 0), r(2, 2));
  } else {  // gimbal lock: put everything in a
    a = std::atan2(r(1, 0), r(0, 0));
    c = 0;
  }
  return Vector3d(a, b, c) * (180.0 / rig::kPi);
}

int single_child(int j) {
  switch (j) {
    case kSpine: return kChest;
    case kNeck: return kHead;
    case kLeftHip: case kLeftKnee: case kLeftAnkle:
    case kRightHip: case kRightKnee: case kRightAnkle:
    case kLeftShoulder: case kLeftElbow: case kRightShoulder: case kRightElbow: return j + 1;
    default: return -1;
  }
}

// Standing height implied by the bone lengths of a pose (canonical proportions).
double implied_height_m(const Pose& p) {
  const Pose unit = canonical_rest_offsets(100);
  double len = 0, unit_len = 0;
  for (int j = 1; j < kJointCount; ++j) {
    len += (p[j] - p[joint_parent(j)]).norm();
    unit_len += unit[j].norm();
  }
  return len / unit_len;
}

}  // namespace

Bvh motion_to_bvh(const Motion& motion) {
  if (motion.frames.empty()) throw Error(motion.name + ": cannot write a motion with no frames as BVH");
  if (!(motion.fps > 0)) throw Error(motion.name + ": expected a positive frame rate");
  const double h = implied_height_m(motion.frames.front());
  const Pose o = canonical_rest_offsets(h * 100);

  Bvh bvh;
  bvh.source = motion.name;
  bvh.frame_time = 1.0 / motion.fps;
  std::array<int, kJointCount> index{};  // canonical joint -> BVH joint
  for (int i = 0; i < kJointCount; ++i) index[kFileOrder[i]] = i;
  int column = 0;
  for (int j : kFileOrder) {
    BvhJoint b;
    b.name = joint_name(j);
    b.parent = j == kPelvis ? -1 : index[joint_parent(j)];
    b.offset = j == kPelvis ? Vector3d::Zero() : to_bvh_cm(o[j]);
    if (j == kPelvis)
      b.channels = {Channel::Xposition, Channel::Yposition, Channel::Zposition,
                    Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    else
      b.channels = {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation};
    b.first_channel = column;
    column += int(b.channels.size());
    if (j == kHead) {
      b.has_end_site = true;
      b.end_site = to_bvh_cm(Vector3d(0, 0, 0.130 * h));  // head top (team skeleton)
    } else if (j == kLeftToe || j == kRightToe) {
      b.has_end_site = true;
      b.end_site = to_bvh_cm((rig::kToeTipPoint - rig::kToeOffset) * h);
    } else if (j == kLeftWrist || j == kRightWrist) {
      b.has_end_site = true;
      b.end_site = to_bvh_cm(Vector3d(0, 0, -anthropometry::kDrillisContini.hand * h));
    }
    bvh.joints.push_back(b);
  }
  bvh.channel_count = column;

  const Matrix3d pm = bvh_to_world();
  bvh.values.reserve(std::size_t(motion.size()) * column);
  std::array<Matrix3d, kJointCount> world;
  for (const Pose& p : motion.frames) {
    for (int j : kFileOrder) {
      const int parent = joint_parent(j);
      const Matrix3d r_parent = parent < 0 ? Matrix3d::Identity() : world[parent];
      Matrix3d local = Matrix3d::Identity();
      if (j == kPelvis) {
        world[j] = frame_from(p[kLeftHip] - p[kRightHip], p[kSpine] - p[kPelvis]);
      } else if (j == kChest) {
        world[j] = frame_from(p[kLeftShoulder] - p[kRightShoulder], p[kNeck] - p[kChest]);
      } else {
        const int child = single_child(j);
        if (child >= 0) {
          const Vector3d now = r_parent.transpose() * (p[child] - p[j]);
          if (now.norm() > 1e-12)
            local = Eigen::Quaterniond::FromTwoVectors(o[child], now).toRotationMatrix();
        }
        world[j] = r_parent * local;
      }
      local = r_parent.transpose() * world[j];
      if (j == kPelvis) {
        const Vector3d pos = to_bvh_cm(p[kPelvis]);
        bvh.values.insert(bvh.values.end(), {pos.x(), pos.y(), pos.z()});
      }
      const Vector3d e = zxy_degrees(pm.transpose() * local * pm);
      bvh.values.insert(bvh.values.end(), {e.x(), e.y(), e.z()});
    }
  }
  return bvh;
}

}  // namespace ptnet
