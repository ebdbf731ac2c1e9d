// Internal: steps every motion loader shares (BVH and marker files).
#pragma once

#include <cmath>

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

// Throws Error unless options.fps is a rate a motion may be read at: a
// finite number <= 0 (the file's own) or in kReadFpsRange.
void check_read_fps(const MotionOptions& options);
// True when a file recorded at `file_fps` is read as it is for `fps`: the
// same rate, its header's number rounded to a few digits (1e-4 relative;
// a BVH's Frame Time 0.016667 is 60 fps). The motion is then at `fps`.
inline bool same_rate(double file_fps, double fps) { return std::abs(file_fps - fps) <= 1e-4 * fps; }

// The motion at `fps`, each joint interpolated linearly between the frames
// either side (positions of a marker recording, not rotations).
Motion resample_linear(const Motion& motion, double fps);

}  // namespace ptnet::detail
