// Placement of a motion on the mat: centred, walking direction along the
// long axis (row 0 = the far end the body walks towards), the body's left
// towards col 0; decided once per source motion and scaled to its copies.
// Also what a placement corrects: the floor under a motion, the feet's
// pitch and their height (foot lifts, from the soles' lowest points:
// sole_lowest.cpp); and the frozen-pelvis check.
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/smooth.hpp"
#include "ptnet/error.hpp"
#include "sim_internal.hpp"

namespace ptnet::detail {

namespace {

constexpr double kPlantedMps = 0.15;  // a joint slower than this (horizontally) is planted

// Per frame, the lowest planted sole (1e300: none), two kinds: [0] a
// hindfoot that is nearly level (< ~7 degrees) under a still ankle (a foot
// flat on the floor; heel strikes and toe-offs do not count: their rigid
// sole reaches lower than the real, rolling one); [1] the sole under a still
// toe joint while the heel is raised (a forefoot stance: a sprint, a dancer
// on the balls of the feet), whose level the marker-placed toe joint gives
// less well (1-2 cm high in walking push-offs): used only where no flat foot
// is near.
std::array<std::vector<double>, 2> planted_soles(const Motion& motion, const Body& body) {
  const int T = motion.size();
  const double fps = motion.fps > 0 ? motion.fps : 30;
  std::array<std::vector<double>, 2> out{std::vector<double>(std::size_t(T), 1e300),
                                         std::vector<double>(std::size_t(T), 1e300)};
  for (int t = 0; t < T; ++t) {
    const PosedBody pb = pose_body(body, motion.frames[std::size_t(t)]);
    const int t0 = std::max(0, t - 1), t1 = std::min(T - 1, t + 1);
    for (int s = 0; s < 2; ++s) {
      const auto& f = s ? pb.right_foot : pb.left_foot;
      for (int kind = 0; kind < 2; ++kind) {
        const int j = (s ? kRightAnkle : kLeftAnkle) + kind;  // the ankle, then the toe joint
        const double speed =
            t1 > t0 ? (motion.frames[std::size_t(t1)][j] - motion.frames[std::size_t(t0)][j]).head<2>().norm() * fps / (t1 - t0)
                    : 0.0;
        const double slope = f[0].forward.z();
        if (speed < kPlantedMps && (kind == 0 ? std::abs(slope) < 0.12 : slope < -0.12))
          out[std::size_t(kind)][std::size_t(t)] = std::min(out[std::size_t(kind)][std::size_t(t)], f[std::size_t(kind)].origin.z());
      }
    }
  }
  return out;
}

}  // namespace

std::vector<double> floor_track(const Motion& motion, const Body& body, double window_s, double max_m) {
  const int T = motion.size();
  std::vector<double> floor(static_cast<std::size_t>(T), 0.0);
  if (!(window_s > 0) || T == 0) return floor;
  const double fps = motion.fps > 0 ? motion.fps : 30;
  // The floor is where planted feet stand, followed over the window.
  const std::array<std::vector<double>, 2> planted = planted_soles(motion, body);
  const int half = std::max(1, int(std::lround(0.5 * window_s * fps)));
  bool any = false;
  for (int t = 0; t < T; ++t) {
    std::array<double, 2> m{1e300, 1e300};
    for (int k = std::max(0, t - half); k <= std::min(T - 1, t + half); ++k)
      for (int kind = 0; kind < 2; ++kind) m[std::size_t(kind)] = std::min(m[std::size_t(kind)], planted[std::size_t(kind)][std::size_t(k)]);
    const double level = m[0] < 1e299 ? m[0] : m[1];
    if (level < 1e299) {
      floor[std::size_t(t)] = std::clamp(level, -max_m, max_m);
      any = true;
    } else {
      floor[std::size_t(t)] = std::nan("");
    }
  }
  if (!any) return std::vector<double>(std::size_t(T), 0.0);
  // Hold the last known floor across frames with no planted foot.
  double last = std::nan("");
  for (int t = 0; t < T; ++t)
    if (std::isnan(floor[std::size_t(t)])) floor[std::size_t(t)] = last; else last = floor[std::size_t(t)];
  last = std::nan("");
  for (int t = T - 1; t >= 0; --t)
    if (std::isnan(floor[std::size_t(t)])) floor[std::size_t(t)] = last; else last = floor[std::size_t(t)];
  return gaussian_smooth(floor, 0.5 * half);
}

std::array<double, 2> foot_pitch_offsets(const Motion& motion) {
  // Canonical rest pitch of ankle -> toe joint below the horizontal: the
  // ankle 0.039 H and the toe joint 0.009 H above the ground, 0.079 H apart.
  const double rest = rest_foot_pitch();
  const int T = motion.size();
  const double fps = motion.fps > 0 ? motion.fps : 30;
  std::array<double, 2> out{0, 0};
  for (int s = 0; s < 2; ++s) {
    const int a = s ? kRightAnkle : kLeftAnkle, b = a + 1;
    std::vector<double> pitch;
    for (int t = 1; t + 1 < T; ++t) {
      const Pose& p = motion.frames[std::size_t(t)];
      const double v = (motion.frames[std::size_t(t + 1)][a] - motion.frames[std::size_t(t - 1)][a]).head<2>().norm() * fps / 2;
      if (v > 0.05) continue;  // planted: the ankle barely moves
      const Eigen::Vector3d d = p[b] - p[a];
      pitch.push_back(std::atan2(-d.z(), d.head<2>().norm()));
    }
    if (pitch.size() < 5) continue;
    // Most planted frames are the foot flat on the floor: the median.
    const std::size_t q = pitch.size() / 2;
    std::nth_element(pitch.begin(), pitch.begin() + std::ptrdiff_t(q), pitch.end());
    out[std::size_t(s)] = std::clamp(rest - pitch[q], -0.5, 0.5);
  }
  return out;
}

double frozen_pelvis_fraction(const Motion& motion) {
  constexpr double kStill = 1e-6;   // m a frame: a height the capture holds exactly
  constexpr double kStepping = 0.3;  // m/s: a foot this fast is stepping
  const int T = motion.size();
  if (T < 2 || !(motion.fps > 0)) return 0;
  const int min_run = std::max(2, int(std::lround(0.5 * motion.fps)));
  int frozen = 0;
  for (int t = 0; t < T;) {
    int end = t + 1;
    bool steps = false;
    while (end < T && std::abs(motion.frames[std::size_t(end)][kPelvis].z() - motion.frames[std::size_t(end - 1)][kPelvis].z()) < kStill) {
      for (int a : {kLeftAnkle, kRightAnkle})
        steps = steps || (motion.frames[std::size_t(end)][a] - motion.frames[std::size_t(end - 1)][a]).head<2>().norm() *
                             motion.fps > kStepping;
      ++end;
    }
    if (end - t >= min_run && steps) frozen += end - t;
    t = end;
  }
  return double(frozen) / T;
}

void lift_feet(Pose& pose, const std::array<double, 2>& lift) {
  for (int s = 0; s < 2; ++s)
    if (lift[std::size_t(s)] != 0)
      for (int j : {s ? kRightAnkle : kLeftAnkle, s ? kRightToe : kLeftToe}) pose[j].z() -= lift[std::size_t(s)];
}

std::array<double, 2> foot_lifts(const Motion& motion, const Body& body, const std::vector<double>& floor) {
  constexpr double kMaxLift = 0.03;  // m: a larger offset is a foot held up (or on a step), not a capture error
  constexpr double kMinLift = 0.005;  // m
  constexpr double kStanceShare = 0.2;  // every foot that stands stands longer than this share of the motion
  const int T = motion.size();
  if (T < 10) return {0, 0};
  std::array<std::vector<double>, 2> z;
  const SoleRows rows(body.sole());
  for (int t = 0; t < T; ++t) {
    const PosedBody pb = pose_body(body, motion.frames[std::size_t(t)]);
    const double f = floor.empty() ? 0.0 : floor[std::size_t(t)];
    for (int s = 0; s < 2; ++s) z[std::size_t(s)].push_back(foot_lowest_z(body.sole(), rows, s ? pb.right_foot : pb.left_foot) - f);
  }
  std::array<double, 2> lift{0, 0};
  for (int s = 0; s < 2; ++s) {
    auto& v = z[std::size_t(s)];
    const std::size_t k = std::size_t(kStanceShare * double(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    // Only a foot that floats is brought down (one below the floor already
    // presses into the foundation), and only when it floats by more than the
    // sole's own relief (a few millimetres a canonical foot stands above).
    if (v[k] > kMinLift && v[k] <= kMaxLift) lift[std::size_t(s)] = v[k];
  }
  return lift;
}

Motion pitch_corrected(const Motion& motion, const std::array<double, 2>& pitch) {
  Motion out = motion;
  if (std::abs(pitch[0]) > 0.03 || std::abs(pitch[1]) > 0.03)  // ~2 degrees
    for (Pose& p : out.frames) pitch_feet(p, pitch);
  return out;
}

}  // namespace ptnet::detail

namespace ptnet {

namespace {

// The mat's long axis (a unit vector, world x-y): the major axis of the
// pelvis path about its mean, pointed the way the body travels (or faces,
// for a round trip); the facing direction for a body that stays in place.
Eigen::Vector2d mat_axis(const Motion& motion) {
  const int T = motion.size();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero(), facing = Eigen::Vector2d::Zero();
  for (const auto& pose : motion.frames) {
    mean += pose[kPelvis].head<2>();
    // Facing = (left hip - right hip) turned 90 degrees clockwise.
    Eigen::Vector2d lr = (pose[kLeftHip] - pose[kRightHip]).head<2>();
    Eigen::Vector2d f(lr.y(), -lr.x());
    if (f.norm() > 1e-9) facing += f.normalized();
  }
  mean /= T;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& pose : motion.frames) {
    Eigen::Vector2d d = pose[kPelvis].head<2>() - mean;
    cov += d * d.transpose();
  }
  cov /= T;
  // Major axis of the 2 x 2 covariance in closed form.
  const double a = cov(0, 0), b = cov(0, 1), c = cov(1, 1);
  const double angle = 0.5 * std::atan2(2 * b, a - c);
  Eigen::Vector2d axis(std::cos(angle), std::sin(angle));
  double lo = 1e300, hi = -1e300;
  for (const auto& pose : motion.frames) {
    double s = axis.dot(pose[kPelvis].head<2>() - mean);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  const bool moves = hi - lo > 0.3;  // m: less is standing / exercising in place
  if (!moves) {
    axis = facing.norm() > 1e-6 ? Eigen::Vector2d(facing.normalized()) : Eigen::Vector2d(1, 0);
  } else {
    // Point the axis the way the body travels (or faces, for a round trip).
    double travel = axis.dot((motion.frames.back()[kPelvis] - motion.frames.front()[kPelvis]).head<2>());
    double sign = std::abs(travel) > 0.1 ? travel : axis.dot(facing);
    if (sign < 0) axis = -axis;
  }
  return axis;
}

// Placement::fixed: the centre of the pelvis path's bounding box in mat axes.
Eigen::Vector2d fixed_centre(const Motion& motion, const Eigen::Vector2d& axis, const Eigen::Vector2d& left) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& pose : motion.frames) {
    Eigen::Vector2d p = pose[kPelvis].head<2>();
    x0 = std::min(x0, axis.dot(p)), x1 = std::max(x1, axis.dot(p));
    y0 = std::min(y0, left.dot(p)), y1 = std::max(y1, left.dot(p));
  }
  return 0.5 * (x0 + x1) * axis + 0.5 * (y0 + y1) * left;
}

// Placement::follow: the pelvis path smoothed (Gaussian, follow_smoothing_s),
// one centre per frame.
std::vector<Eigen::Vector2d> followed_centres(const Motion& motion, const SimOptions& options) {
  const int T = motion.size();
  std::vector<double> px(T), py(T);
  for (int t = 0; t < T; ++t) {
    px[t] = motion.frames[t][kPelvis].x();
    py[t] = motion.frames[t][kPelvis].y();
  }
  // Smoothing near the ends: the path is extended by its point reflection
  // through the end point, so that steady walking is followed without lag.
  const double sigma = options.follow_smoothing_s * motion.fps;
  auto smooth_path = [&](const std::vector<double>& x) {
    const int pad = std::min(T - 1, int(std::ceil(3 * sigma)));
    std::vector<double> ext;
    ext.reserve(std::size_t(T + 2 * pad));
    for (int k = pad; k >= 1; --k) ext.push_back(2 * x[0] - x[std::size_t(k)]);
    ext.insert(ext.end(), x.begin(), x.end());
    for (int k = 1; k <= pad; ++k) ext.push_back(2 * x[std::size_t(T - 1)] - x[std::size_t(T - 1 - k)]);
    ext = gaussian_smooth(ext, sigma);
    return std::vector<double>(ext.begin() + pad, ext.begin() + pad + T);
  };
  px = smooth_path(px);
  py = smooth_path(py);
  std::vector<Eigen::Vector2d> centres(T);
  for (int t = 0; t < T; ++t) centres[t] = Eigen::Vector2d(px[t], py[t]);
  return centres;
}

}  // namespace

const Body& detail::reference_body() {
  static const Body body([] {
    BodySpec spec;
    spec.id = "floor-reference";
    spec.sex = Sex::male;
    spec.height_cm = kFloorReferenceHeightCm;
    spec.weight_kg = 65;
    return spec;
  }());
  return body;
}

namespace {

// The feet's pitch and the floor of the copy at a reference height (on a
// reference body), the floor scaled back: a retargeted copy is this one
// scaled by the height ratio, and so is its floor, whatever the body's
// girth; its angles are this copy's.
void place_feet_and_floor(const Motion& motion, const SimOptions& options, MotionPlacement& out) {
  const Motion reference = retarget(motion, kFloorReferenceHeightCm);
  const double ratio = retarget_scale(motion, kFloorReferenceHeightCm);
  out.foot_pitch = detail::foot_pitch_offsets(reference);
  const Motion corrected = detail::pitch_corrected(reference, out.foot_pitch);
  std::vector<double> floor;  // the reference copy's
  if (options.floor_window_s > 0) {
    floor = detail::floor_track(corrected, detail::reference_body(), options.floor_window_s, 0.25);
    out.floor = floor;
    for (double& z : out.floor) z /= ratio;
  }
  out.foot_lift = detail::foot_lifts(corrected, detail::reference_body(), floor);
  for (double& z : out.foot_lift) z /= ratio;
}

}  // namespace

MotionPlacement place_motion(const Motion& motion, const SimOptions& options) {
  const int T = motion.size();
  if (T == 0) throw Error("place_motion: motion '" + motion.name + "' has no frames");
  MotionPlacement out;
  out.anchor = motion.frames.front()[kPelvis].head<2>();
  out.axis = mat_axis(motion);
  out.left = Eigen::Vector2d(-out.axis.y(), out.axis.x());
  if (options.placement == Placement::fixed)
    out.centre.assign(T, fixed_centre(motion, out.axis, out.left));
  else
    out.centre = followed_centres(motion, options);
  place_feet_and_floor(motion, options, out);
  return out;
}

MotionPlacement MotionPlacement::scaled(double ratio) const {
  if (!(ratio > 0) || !std::isfinite(ratio))
    throw Error("MotionPlacement::scaled: expected a positive ratio, found " + std::to_string(ratio));
  MotionPlacement out = *this;
  for (Eigen::Vector2d& c : out.centre) c = anchor + ratio * (c - anchor);
  for (double& z : out.floor) z *= ratio;
  for (double& z : out.foot_lift) z *= ratio;
  return out;
}

MotionPlacement place_copy(const Motion& source, double height_cm, const SimOptions& options) {
  return place_motion(source, options).scaled(retarget_scale(source, height_cm));
}

}  // namespace ptnet
