// Internal: the motion stage's own functions (BVH text, forward
// kinematics, resampling, the belt, the canonical skeleton) and the steps
// every motion loader shares (BVH and marker files). Tests include it as
// "motion/motion_internal.hpp".
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/rate.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {

// ------------------------------------------------------------------- BVH

// read_bvh on BVH text. `source` names the file in errors, which are one line:
// "walk.bvh:42: expected CHANNELS, found OFFSET".
Bvh parse_bvh(std::string_view text, const std::string& source);
std::string format_bvh(const Bvh& bvh);  // write_bvh's text

// World positions of every BVH joint (not end sites) for every frame:
// [F][J], metres, z up. `scale` is metres per file unit.
std::vector<Eigen::Vector3d> forward_kinematics(const Bvh& bvh, double scale, UpAxis up);
// The same for one frame (J positions appended to `out`).
void forward_kinematics_frame(const Bvh& bvh, int frame, double scale, UpAxis up,
                              std::vector<Eigen::Vector3d>& out);

int joint_parent(int joint);  // of a canonical joint; -1 for the pelvis

// Resamples every channel to `fps`: positions linearly, each joint's rotation
// by quaternion slerp (Euler angles rewritten in the joint's channel order).
Bvh resample(const Bvh& bvh, double fps);

// ----------------------------------------------------------------- motion

// The velocity (world x, y; m/s) of a treadmill belt under `motion`: the
// median horizontal velocity of the lower foot over the frames where it is
// near the floor, when that is over 0.3 m/s while the pelvis travels less
// than a third as fast; zero for a motion overground.
Eigen::Vector2d treadmill_belt_velocity(const Motion& motion);
// without_belt: ptnet/motion.hpp.

// Metres per unit of a named unit (0 for Units::automatic).
double unit_metres(Units units);

// Canonical bone offsets (parent -> joint) in the rest pose, world axes,
// from anthropometric proportions of `height_cm` (arms hanging down).
Pose canonical_rest_offsets(double height_cm);

// Lowest point of the foot soles (heel, toe tip) for one pose, z (m).
double lowest_foot_z(const Pose& pose);

// Sex of a procedural performer, 0 female, 1 male (alternating with
// `performer`); performer_height_cm draws from that sex's stature.
int performer_sex(int performer, std::uint64_t seed = 0);

}  // namespace ptnet

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
// A file recorded at `file_fps` is read as it is for `fps` when
// same_rate(file_fps, fps) (core/rate.hpp); the motion is then at `fps`.

// The motion at `fps`, each joint interpolated linearly between the frames
// either side (positions of a marker recording, not rotations).
Motion resample_linear(const Motion& motion, double fps);

}  // namespace ptnet::detail
