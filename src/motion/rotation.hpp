// Internal helpers of the motion stage: BVH channel rotations, Euler angles
// in any axis order, the BVH-to-world axis map. Not a public header.
#pragma once

#include <Eigen/Geometry>
#include <array>

#include "ptnet/motion.hpp"

namespace ptnet::detail {

constexpr double kDegToRad = 0.017453292519943295;
constexpr double kRadToDeg = 57.29577951308232;

inline bool is_rotation(Channel c) { return int(c) >= int(Channel::Xrotation); }
inline int channel_axis(Channel c) { return int(c) % 3; }  // 0 x, 1 y, 2 z

// A vector in file axes -> world axes (z up). y-up: (x, y, z) -> (z, x, y).
inline Eigen::Vector3d to_world(const Eigen::Vector3d& v, UpAxis up) {
  return up == UpAxis::y ? Eigen::Vector3d(v.z(), v.x(), v.y()) : v;
}

// The joint's local rotation from its rotation channels (degrees), composed
// in channel order: R = R_c1 * R_c2 * R_c3.
inline Eigen::Quaterniond joint_rotation(const BvhJoint& joint, const double* frame) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (std::size_t i = 0; i < joint.channels.size(); ++i) {
    Channel c = joint.channels[i];
    if (!is_rotation(c)) continue;
    q = q * Eigen::Quaterniond(Eigen::AngleAxisd(frame[joint.first_channel + int(i)] * kDegToRad,
                                                 Eigen::Vector3d::Unit(channel_axis(c))));
  }
  return q;
}

// Angles (rad) a, b, c with R = R_i(a) R_j(b) R_k(c) for distinct axes
// i, j, k; b in [-pi/2, pi/2]. At gimbal lock c = 0.
inline Eigen::Vector3d euler_angles(const Eigen::Matrix3d& R, int i, int j, int k) {
  const double s = (j == (i + 1) % 3) ? 1.0 : -1.0;  // even permutation
  double sb = s * R(i, k);
  sb = sb > 1 ? 1 : (sb < -1 ? -1 : sb);
  const double b = std::asin(sb);
  if (std::abs(sb) > 1 - 1e-12) {
    return {std::atan2(s * R(k, j), R(j, j)), b, 0.0};
  }
  return {std::atan2(-s * R(j, k), R(k, k)), b, std::atan2(-s * R(i, j), R(i, i))};
}

// Rotation whose y axis is along `lateral` and z axis along `up` made
// orthogonal to it (x = y cross z); identity when degenerate. Used to place
// the pelvis and chest groups (retargeting) and to write their BVH rotations.
inline Eigen::Matrix3d frame_from(const Eigen::Vector3d& lateral, const Eigen::Vector3d& up) {
  if (lateral.norm() < 1e-12) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d y = lateral.normalized();
  Eigen::Vector3d z = up - up.dot(y) * y;
  if (z.norm() < 1e-12) return Eigen::Matrix3d::Identity();
  z.normalize();
  Eigen::Matrix3d r;
  r.col(0) = y.cross(z);
  r.col(1) = y;
  r.col(2) = z;
  return r;
}

}  // namespace ptnet::detail
