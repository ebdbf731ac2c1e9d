// Measurements on canonical poses: the lowest sole point and the standing
// height. Both use the canonical foot and head geometry of the team notes
// (Drillis-Contini proportions via src/core/anthropometry.hpp):
//   toe (MTP) = ankle + (0.0790 H, 0, -0.030 H)         (|toe - ankle| = 0.0845 H)
//   heel back = ankle + (-0.0334 H, 0, -0.039 H)
//   toe tip   = toe   + (+0.0395 H, 0, -0.009 H)
//   head top  = head  + 0.130 H                          (head at 0.870 H)
// so that the canonical skeleton of height H stands with heel and toe tip at
// z = 0 and measures exactly H.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "core/anthropometry.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {
namespace {

namespace A = anthropometry;

// Rest-pose foot vectors (fractions of H), x forward, z up.
const Eigen::Vector3d kToeRest(
    A::kDrillisContini.foot_length* A::kFoot.mtp - A::kDrillisContini.foot_length * A::kFoot.ankle,
    0, A::kFoot.mtp_height - A::kDrillisContini.ankle);  // (0.0790, 0, -0.030)
const Eigen::Vector3d kHeelRest(-A::kDrillisContini.foot_length* A::kFoot.ankle, 0,
                                -A::kDrillisContini.ankle);  // (-0.0334, 0, -0.039)
const Eigen::Vector3d kTipRest(A::kDrillisContini.foot_length*(1 - A::kFoot.mtp), 0,
                               -A::kFoot.mtp_height);       // (0.0395, 0, -0.009)
constexpr double kHeadTop = 1.0 - A::kDrillisContini.chin;  // 0.130 H above the head joint

// A vector in the rest foot's sagittal frame (u along ankle->toe, w normal
// to it pointing up): (a, b) coordinates.
Eigen::Vector2d in_foot_frame(const Eigen::Vector3d& v) {
  const Eigen::Vector3d u = kToeRest.normalized();
  const Eigen::Vector3d w(-u.z(), 0, u.x());
  return {v.dot(u), v.dot(w)};
}

}  // namespace

namespace detail {

SolePoints sole_points(const Eigen::Vector3d& ankle, const Eigen::Vector3d& toe) {
  const Eigen::Vector3d d = toe - ankle;
  const double length = d.norm();
  if (length < 1e-9) return {ankle, toe};
  const double H = length / kToeRest.norm();
  const Eigen::Vector3d u = d / length;
  // w: in the vertical plane through the foot, normal to u, pointing up.
  Eigen::Vector3d w = Eigen::Vector3d::UnitZ() - u.z() * u;
  if (w.norm() < 1e-6) w = Eigen::Vector3d::UnitX() - u.x() * u;  // foot pointing straight down/up
  w.normalize();
  static const Eigen::Vector2d heel = in_foot_frame(kHeelRest);
  static const Eigen::Vector2d tip = in_foot_frame(kTipRest);
  return {ankle + H * (heel.x() * u + heel.y() * w), toe + H * (tip.x() * u + tip.y() * w)};
}

double foot_lowest_z(const Eigen::Vector3d& ankle, const Eigen::Vector3d& toe) {
  const SolePoints p = sole_points(ankle, toe);
  return std::min(p.heel.z(), p.tip.z());
}

}  // namespace detail

double lowest_foot_z(const Pose& pose) {
  return std::min(detail::foot_lowest_z(pose[kLeftAnkle], pose[kLeftToe]),
                  detail::foot_lowest_z(pose[kRightAnkle], pose[kRightToe]));
}

double rest_foot_pitch() { return std::atan2(-kToeRest.z(), kToeRest.x()); }

void pitch_feet(Pose& pose, const std::array<double, 2>& offsets) {
  for (int s = 0; s < 2; ++s) {
    if (offsets[std::size_t(s)] == 0) continue;
    const int a = s ? kRightAnkle : kLeftAnkle, b = a + 1;
    const Eigen::Vector3d d = pose[b] - pose[a];
    const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ().cross(d);
    if (axis.norm() < 1e-9) continue;
    // Rotating about z x d by +angle lowers the toe joint (pitches the foot down).
    pose[b] = pose[a] + Eigen::AngleAxisd(offsets[std::size_t(s)], axis.normalized()) * d;
  }
}

std::array<Eigen::Vector3d, 2> foot_ends(const Pose& pose, int side) {
  const detail::SolePoints p = side == 0 ? detail::sole_points(pose[kLeftAnkle], pose[kLeftToe])
                                         : detail::sole_points(pose[kRightAnkle], pose[kRightToe]);
  return {p.heel, p.tip};
}

double standing_height(const Motion& motion) {
  if (motion.frames.empty())
    throw Error::in(motion.name.empty() ? "motion" : motion.name,
                    "no frames to measure a standing height");
  // The first half second (at least one frame): median of the per-frame
  // estimates, robust to a stray frame.
  const int n = std::clamp(int(std::lround(0.5 * motion.fps)), 1, motion.size());
  std::vector<double> h;
  for (int f = 0; f < n; ++f) {
    const Pose& p = motion.frames[std::size_t(f)];
    h.push_back((p[kHead].z() - lowest_foot_z(p)) / (1.0 - kHeadTop));
  }
  std::nth_element(h.begin(), h.begin() + n / 2, h.end());
  return h[std::size_t(n / 2)];
}

}  // namespace ptnet
