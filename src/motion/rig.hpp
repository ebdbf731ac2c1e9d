// Internal: the procedural generator's kinematic model of the canonical
// skeleton (joint angles -> world positions), the planted-foot geometry, and
// the small numeric helpers (splines, easing, seeded random numbers) the
// generators share. Not a public header.
//
// Angles in radians. Sign conventions (world: x forward, y left, z up):
//   trunk pitch > 0 leans forward, roll > 0 bends to the left, yaw > 0 turns left;
//   foot pitch > 0 lifts the toes (pivot on the heel), < 0 lifts the heel
//   (pivot on the toe tip); arm flex > 0 raises the arm forward, abd > 0 out
//   to the side, horiz > 0 swings an abducted arm forward; elbow > 0 bends.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "core/anthropometry.hpp"
#include "ptnet/motion.hpp"

namespace ptnet::rig {

namespace detail {
inline constexpr const auto& kLen = anthropometry::kDrillisContini;
inline constexpr const auto& kFoot = anthropometry::kFoot;
}  // namespace detail

// Foot geometry, fractions of standing height H, in the foot frame (x along
// the sole, z up, origin at the ankle joint centre): the toe (MTP) joint, the
// back of the heel and the toe tip, the latter two on the sole (z = -ankle).
inline const Eigen::Vector3d kToeOffset{(detail::kFoot.mtp - detail::kFoot.ankle) * detail::kLen.foot_length,
                                        0, detail::kFoot.mtp_height - detail::kLen.ankle};
inline const Eigen::Vector3d kHeelPoint{-detail::kFoot.ankle * detail::kLen.foot_length, 0,
                                        -detail::kLen.ankle};
inline const Eigen::Vector3d kToeTipPoint{(1 - detail::kFoot.ankle) * detail::kLen.foot_length, 0,
                                          -detail::kLen.ankle};

constexpr double kPi = 3.14159265358979323846;
inline double deg(double d) { return d * kPi / 180; }

Eigen::Matrix3d rot_x(double a);
Eigen::Matrix3d rot_y(double a);
Eigen::Matrix3d rot_z(double a);
// Trunk-style tilt: forward `pitch`, leftward `roll`, then `yaw` about z.
Eigen::Matrix3d trunk_rotation(double yaw, double pitch, double roll);
// Foot rotation: heading `yaw`, `pitch` > 0 toes up.
Eigen::Matrix3d foot_rotation(double yaw, double pitch);

struct FootPose {
  Eigen::Vector3d ankle = Eigen::Vector3d::Zero();     // m
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};

// A foot on the ground: flat-foot ankle at (xy, ankle height), heading yaw,
// rolled by `pitch` about the heel (pitch > 0) or the toe tip (pitch < 0),
// which stays where it is on the ground. `h` = standing height, m.
FootPose planted_foot(const Eigen::Vector2d& xy, double yaw, double pitch, double h);
// World heel and toe-tip points of a foot pose.
Eigen::Vector3d heel_point(const FootPose& foot, double h);
Eigen::Vector3d toe_tip_point(const FootPose& foot, double h);
double foot_lowest_z(const FootPose& foot, double h);

struct Arm {
  double flex = 0, abd = 0, horiz = 0, elbow = 0;
};

// Every degree of freedom of one frame of the generator's model.
struct Controls {
  Eigen::Vector3d pelvis = Eigen::Vector3d::Zero();  // m
  double yaw = 0, pitch = 0, roll = 0;               // pelvis
  double trunk_pitch = 0, trunk_roll = 0, trunk_yaw = 0;  // spine + chest, split evenly
  double head_pitch = 0, head_yaw = 0;
  std::array<Arm, 2> arm;        // [left, right]
  std::array<FootPose, 2> foot;  // [left, right]; legs follow by two-bone IK
};

// Highest pelvis z (m) at which both ankles are still reached with the knees
// at most `straight` of full extension.
double max_pelvis_z(const Controls& c, const Pose& offsets, double straight = 0.998);

// World positions of the canonical joints for one frame (bone lengths exact).
Pose evaluate(const Controls& c, const Pose& offsets);

// Sets pelvis z = min(nominal, reachable) and smooths it without ever exceeding
// the reachable height (erosion then box mean of radius ~0.1 s). `nominal` [F], m.
void settle_pelvis_heights(std::vector<Controls>& frames, const std::vector<double>& nominal,
                           const Pose& offsets, double fps);

// ------------------------------------------------------------ numeric helpers

double smoothstep(double x);  // 3x^2 - 2x^3 on [0, 1], clamped
double min_jerk(double x);    // 10x^3 - 15x^4 + 6x^5 on [0, 1], clamped
double wrap_angle(double a);  // to (-pi, pi]

// Piecewise cubic Hermite through (t, value) keys with finite-difference
// (Catmull-Rom) tangents; constant beyond the ends. Keys sorted by t.
class Spline {
 public:
  void add(double t, const Eigen::Vector3d& v) { keys_.push_back({t, v}); }
  Eigen::Vector3d operator()(double t) const;
  bool empty() const { return keys_.empty(); }

 private:
  struct Key {
    double t;
    Eigen::Vector3d v;
  };
  std::vector<Key> keys_;
};

// Seeded random numbers with the same sequence on every platform
// (std::mt19937_64 raw output; no std distributions).
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0);
  double uniform(double lo, double hi);
  double normal(double mean, double sd);
  int integer(int lo, int hi);  // inclusive
  bool chance(double p) { return uniform(0, 1) < p; }
  std::uint64_t bits();

 private:
  std::mt19937_64 engine_;
};

}  // namespace ptnet::rig
