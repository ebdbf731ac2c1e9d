// Internal: steps every motion loader shares (BVH and marker files).
#pragma once

#include "ptnet/motion.hpp"

namespace ptnet::detail {

// The back of the heel and the toe tip of a foot (world, m) from its ankle
// and toe joints, by the canonical foot geometry scaled to the bone's length.
struct SolePoints {
  Eigen::Vector3d heel, tip;
};
SolePoints sole_points(const Eigen::Vector3d& ankle, const Eigen::Vector3d& toe);
// The lower of the two's heights.
double foot_lowest_z(const Eigen::Vector3d& ankle, const Eigen::Vector3d& toe);

// Shifts z so that the floor, the lower quartile over frames of the lowest
// sole point (lowest_foot_z), is at z = 0: robust to airborne phases and to
// stretches of feet through the floor (CMU 141_15 squats sink the toes 10 cm
// for a tenth of the clip).
void ground(Motion& motion);

// The motion at `fps`, each joint interpolated linearly between the frames
// either side (positions of a marker recording, not rotations).
Motion resample_linear(const Motion& motion, double fps);

}  // namespace ptnet::detail
