// T-pose detection: arms out horizontally, legs straight and vertical.
// CMU conversions (cgspeed) prepend such a calibration frame to every clip.
#include <cmath>
#include <vector>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {
namespace {

constexpr double kArmMaxSlope = 0.34;     // |sin| of an arm segment's elevation (~20 deg)
constexpr double kArmMinOutward = 0.80;   // cos of the angle to the shoulder line (~37 deg)
constexpr double kLegMinVertical = 0.90;  // cos of a leg segment's angle to -z (~26 deg)

Eigen::Vector3d unit(const Eigen::Vector3d& v) {
  const double n = v.norm();
  return n > 1e-12 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
}

}  // namespace

bool is_tpose(const Bvh& bvh, int frame, const std::array<int, kJointCount>& map, double scale,
              UpAxis up) {
  std::vector<Eigen::Vector3d> p;
  forward_kinematics_frame(bvh, frame, scale, up, p);
  auto at = [&](int k) { return p[std::size_t(map[std::size_t(k)])]; };
  const Eigen::Vector3d across = unit(at(kLeftShoulder) - at(kRightShoulder));  // to the left
  if (across.isZero()) return false;
  const int arms[2][3] = {{kLeftShoulder, kLeftElbow, kLeftWrist},
                          {kRightShoulder, kRightElbow, kRightWrist}};
  for (int side = 0; side < 2; ++side) {
    const Eigen::Vector3d outward = side == 0 ? across : Eigen::Vector3d(-across);
    for (int seg = 0; seg < 2; ++seg) {
      const Eigen::Vector3d d = unit(at(arms[side][seg + 1]) - at(arms[side][seg]));
      if (std::abs(d.z()) > kArmMaxSlope || d.dot(outward) < kArmMinOutward) return false;
    }
  }
  const int legs[2][3] = {{kLeftHip, kLeftKnee, kLeftAnkle}, {kRightHip, kRightKnee, kRightAnkle}};
  for (const auto& leg : legs)
    for (int seg = 0; seg < 2; ++seg) {
      const Eigen::Vector3d d = unit(at(leg[seg + 1]) - at(leg[seg]));
      if (-d.z() < kLegMinVertical) return false;
    }
  return true;
}

}  // namespace ptnet
