// A treadmill's belt under a motion: found from the planted foot moving
// backwards while the pelvis stays, and removed so that the same gait is
// simulated overground (the planted foot still, the body travelling).
#include <algorithm>
#include <cmath>
#include <vector>

#include "motion_internal.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {
namespace {

constexpr double kPlantedBand = 0.03;        // m above the foot's lowest sole point (10th percentile)
constexpr double kMinBeltSpeed = 0.3;        // m/s: slower is a foot sliding overground
constexpr double kMaxTravelRatio = 1.0 / 3;  // the pelvis travels at most this fraction of the belt speed

double median(std::vector<double> v) {
  const std::size_t k = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

// The heel back (tip false) or toe tip of foot s (0 left, 1 right) in frame t.
Eigen::Vector3d sole_point(const Motion& m, int s, int t, bool tip) {
  const Pose& p = m.frames[std::size_t(t)];
  const detail::SolePoints q =
      s == 0 ? detail::sole_points(p[kLeftAnkle], p[kLeftToe]) : detail::sole_points(p[kRightAnkle], p[kRightToe]);
  return tip ? q.tip : q.heel;
}

}  // namespace

Eigen::Vector2d treadmill_belt_velocity(const Motion& motion) {
  const int T = motion.size();
  if (T < 5 || !(motion.fps > 0)) return Eigen::Vector2d::Zero();
  // The point of a foot that touches the belt moves with it: the lower of
  // the heel back and the toe tip of the lower foot, when near the floor.
  auto lowest = [&](int s, int t) {
    return std::min(sole_point(motion, s, t, false).z(), sole_point(motion, s, t, true).z());
  };
  double low[2];
  for (int s = 0; s < 2; ++s) {
    std::vector<double> z;
    for (int t = 0; t < T; ++t) z.push_back(lowest(s, t));
    std::nth_element(z.begin(), z.begin() + std::ptrdiff_t(z.size() / 10), z.end());
    low[s] = z[z.size() / 10];
  }
  std::vector<double> vx, vy;
  for (int t = 1; t + 1 < T; ++t) {
    const double z0 = lowest(0, t) - low[0], z1 = lowest(1, t) - low[1];
    const int s = z0 < z1 ? 0 : 1;
    if (std::min(z0, z1) > kPlantedBand) continue;
    const bool tip = sole_point(motion, s, t, true).z() < sole_point(motion, s, t, false).z();
    const Eigen::Vector3d v = (sole_point(motion, s, t + 1, tip) - sole_point(motion, s, t - 1, tip)) * (0.5 * motion.fps);
    vx.push_back(v.x());
    vy.push_back(v.y());
  }
  if (vx.size() < 3) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d belt(median(vx), median(vy));
  const Eigen::Vector3d travel = motion.frames.back()[kPelvis] - motion.frames.front()[kPelvis];
  const double pelvis_speed = travel.head<2>().norm() * motion.fps / (T - 1);
  if (belt.norm() < kMinBeltSpeed || pelvis_speed > kMaxTravelRatio * belt.norm()) return Eigen::Vector2d::Zero();
  return belt;
}

Motion without_belt(Motion motion, const Eigen::Vector2d& velocity) {
  for (int t = 0; t < motion.size(); ++t) {
    const Eigen::Vector2d shift = velocity * (t / motion.fps);
    for (Eigen::Vector3d& j : motion.frames[std::size_t(t)]) j.head<2>() -= shift;
  }
  return motion;
}

}  // namespace ptnet
