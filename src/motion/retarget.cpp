// Retargeting onto a body of a given height (canonical bone lengths).
//
// Joint rotations kept, up to bone twist: every bone keeps its world
// direction per frame and takes the target's length. The two rigid groups of
// the canonical skeleton, the pelvis (spine, hips) and the chest (neck,
// shoulders), are placed by the frame of their bones in the source (lateral
// axis from right to left joint, up axis towards spine / neck), since the
// canonical hip and shoulder offsets need not point the way the source rig's
// do. The root translation scales with leg length, and each frame is moved
// up or down so that the supporting ankle stands where the scaled source's
// does (support_correction); the motion is re-grounded so that the lowest
// foot point during stance is at z = 0.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/smooth.hpp"
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
constexpr double kSupportBand = 0.02;       // m: a foot this much above the lower one has e^-1 of its weight
constexpr double kSupportSmoothS = 0.05;    // s: Gaussian sigma of the support correction
constexpr double kPlantedMps = 0.25;        // m/s: a foot's ankle slower than this is planted ...
constexpr double kPlantedBandM = 0.03;      // m: ... when it is this close to its lowest level
constexpr double kSwingWeight = 0.02;       // a foot not planted, against a planted one

double leg_length(const Pose& p) {
  double sum = 0;
  for (int hip : {kLeftHip, kRightHip})
    sum += (p[hip + 1] - p[hip]).norm() + (p[hip + 2] - p[hip + 1]).norm();
  return 0.5 * sum;
}

// Each foot's ankle height in the source (m, [2][T]) and whether the foot
// is planted (its ankle slower than kPlantedMps, within kPlantedBandM of its
// lowest level): a planted foot stands on the floor.
struct AnkleHeights {
  std::array<std::vector<double>, 2> z;      // [2][T] m
  std::array<std::vector<bool>, 2> planted;  // [2][T]
};

AnkleHeights planted_ankle_heights(const Motion& source) {
  const std::size_t T = source.frames.size();
  const double fps = source.fps > 0 ? source.fps : 30;
  AnkleHeights out;
  for (int s = 0; s < 2; ++s) {
    const int ankle = s ? kRightAnkle : kLeftAnkle;
    std::vector<double>& zs = out.z[std::size_t(s)];
    for (const Pose& p : source.frames) zs.push_back(p[ankle].z());
    std::vector<double> sorted = zs;
    const std::size_t k = sorted.size() / 10;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    std::vector<bool>& planted = out.planted[std::size_t(s)];
    planted.assign(T, false);
    for (std::size_t t = 0; t < T; ++t) {
      const std::size_t t0 = t > 0 ? t - 1 : t, t1 = t + 1 < T ? t + 1 : t;
      const double speed =
          t1 > t0 ? (source.frames[t1][ankle] - source.frames[t0][ankle]).head<2>().norm() * fps / double(t1 - t0) : 0.0;
      planted[t] = speed < kPlantedMps && zs[t] < sorted[k] + kPlantedBandM;
    }
  }
  return out;
}

// The vertical shift of each frame of `copy` that puts its supporting foot
// where the source's is, scaled by `ratio` (m, [T]). A copy of canonical
// proportions does not reach where the source's legs did: marker-derived
// bones change length as the knee bends (the thighs of a squat trial look
// 5 cm shorter at its bottom than standing), and a rig's thigh : shank ratio
// is not the canonical one; with the root height scaled by the mean leg
// ratio alone, the feet rise off the floor or sink into it as the knees
// bend. Per frame, each ankle's height in the scaled source
// (planted_ankle_heights) less the copy's, weighted towards the planted foot
// (a swinging foot's toes pass 1-2 cm above the floor: kSwingWeight) and
// the lower one (exp(-its height above it / kSupportBand)), smoothed over
// kSupportSmoothS (no step at a change of foot). It follows a posture as fast
// as it changes (sitting down in half a second); the simulator's load leaves
// it out (Motion::support_shift_m), so that it adds no acceleration of its
// own to the centre of mass.
std::vector<double> support_correction(const Motion& source, const std::vector<Pose>& copy, double ratio) {
  const AnkleHeights h = planted_ankle_heights(source);
  std::vector<double> shift(copy.size(), 0.0);
  for (std::size_t t = 0; t < copy.size(); ++t) {
    double d[2], w[2];
    const double low = std::min(h.z[0][t], h.z[1][t]);
    for (int s = 0; s < 2; ++s) {
      const int ankle = s ? kRightAnkle : kLeftAnkle;
      d[s] = ratio * h.z[std::size_t(s)][t] - copy[t][ankle].z();
      w[s] = (h.planted[std::size_t(s)][t] ? 1.0 : kSwingWeight) * std::exp(-(h.z[std::size_t(s)][t] - low) * ratio / kSupportBand);
    }
    shift[t] = (w[0] * d[0] + w[1] * d[1]) / (w[0] + w[1]);
  }
  return gaussian_smooth(shift, kSupportSmoothS * (source.fps > 0 ? source.fps : 30));
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
    out.frames.push_back(q);
  }
  out.support_shift_m = support_correction(motion, out.frames, ratio);
  const std::vector<double>& shift = out.support_shift_m;
  for (std::size_t t = 0; t < out.frames.size(); ++t) {
    for (Vector3d& v : out.frames[t]) v.z() += shift[t];
    lowest.push_back(lowest_foot_z(out.frames[t]));
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
