// Procedural motions: seeding, per-performer style, foot tracks, and the
// common finish (pelvis heights settled so both feet are reached, FK).
#include <algorithm>
#include <cmath>
#include <string>

#include "generate_internal.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {
namespace gen {

using Eigen::Vector2d;
using Eigen::Vector3d;
using rig::deg;

// Ranges: cadence 1.65-1.95 steps/s and stride ~0.8 H (Winter;
// docs/anthropometry.md), slightly shortened for pacing on a 1.6 m mat.
Style performer_style(int performer, std::uint64_t seed, double height_m) {
  rig::Rng rng(seed, 0x5374796c65ULL, std::uint64_t(performer));
  Style s;
  s.height_m = height_m;
  s.cadence = rng.uniform(1.68, 1.92);
  s.stride = rng.uniform(0.70, 0.80);
  s.step_width = rng.uniform(0.055, 0.085);
  s.arm_swing = deg(rng.uniform(12, 24));
  s.trunk_lean = deg(rng.uniform(1, 7));
  s.head_pitch = deg(rng.uniform(-4, 8));
  s.elbow = deg(rng.uniform(8, 25));
  s.knee_soft = rng.uniform(0.004, 0.014);
  s.tempo = rng.uniform(0.85, 1.15);
  s.heel_strike = deg(rng.uniform(12, 20));
  s.toe_off = -deg(rng.uniform(30, 42));
  s.sway = rng.uniform(0.012, 0.022);
  s.toe_out = deg(rng.uniform(3, 10));
  return s;
}

rig::FootPose FootTrack::at(double t, double h, double extra_pitch) const {
  // Last plant whose swing has begun.
  int i = 0;
  while (i + 1 < int(plants.size()) && plants[i + 1].lift <= t) ++i;
  const Plant& p = plants[i];
  if (t >= p.land || i == 0) {
    double pitch = extra_pitch;
    if (t - p.land < p.rocker) pitch += p.land_pitch * (1 - rig::smoothstep((t - p.land) / p.rocker));
    if (i + 1 < int(plants.size())) {
      const double u = (t - (plants[i + 1].lift - p.rise)) / p.rise;
      if (u > 0) pitch += p.leave_pitch * std::min(u, 1.0) * std::min(u, 1.0);
    }
    return rig::planted_foot(p.xy, p.yaw, pitch, h);
  }
  // Swing from plants[i - 1] to p.
  const Plant& q = plants[i - 1];
  const double s = (t - p.lift) / (p.land - p.lift);
  const rig::FootPose a = rig::planted_foot(q.xy, q.yaw, q.leave_pitch, h);
  const rig::FootPose b = rig::planted_foot(p.xy, p.yaw, p.land_pitch, h);
  const double m = rig::min_jerk(s / 0.92);  // horizontally there before touching down
  rig::FootPose f;
  f.ankle.head<2>() = a.ankle.head<2>() + m * (b.ankle.head<2>() - a.ankle.head<2>());
  f.ankle.z() = a.ankle.z() + rig::smoothstep(s) * (b.ankle.z() - a.ankle.z()) +
                p.clearance * std::sin(rig::kPi * std::pow(s, 0.8));
  const double pitch = q.leave_pitch + rig::smoothstep(s / 0.7) * (p.land_pitch - q.leave_pitch);
  const double yaw = q.yaw + m * rig::wrap_angle(p.yaw - q.yaw);
  f.rotation = rig::foot_rotation(yaw, pitch);
  const double low = rig::foot_lowest_z(f, h);
  if (low < 0) f.ankle.z() -= low;  // never through the floor
  return f;
}

double FootTrack::swing_activity(double t, double ramp) const {
  double a = 0;
  for (std::size_t i = 1; i < plants.size(); ++i) {
    const Plant& p = plants[i];
    if (t < p.lift - ramp || t > p.land + ramp) continue;
    double v = 1;
    if (t < p.lift) v = rig::smoothstep((t - (p.lift - ramp)) / ramp);
    if (t > p.land) v = 1 - rig::smoothstep((t - p.land) / ramp);
    a = std::max(a, v);
  }
  return a;
}

}  // namespace gen

Motion generate_motion(const GenerateOptions& options) {
  if (!(options.seconds > 0) || options.seconds > 3600)
    throw Error("generate_motion: expected seconds in (0, 3600], found " + number_text(options.seconds));
  check_range("fps", options.fps, kFpsRange);
  if (options.performer < 1 || options.take < 1)
    throw Error("generate_motion: expected performer and take >= 1, found " +
                std::to_string(options.performer) + " and " + std::to_string(options.take));
  if (!(options.height_cm == 0 || (options.height_cm >= 50 && options.height_cm <= 250)))
    throw Error("generate_motion: height_cm: expected 0 (the performer's own) or a height in [50, 250] cm, found " +
                number_text(options.height_cm));
  const double height_cm =
      options.height_cm > 0 ? options.height_cm : performer_height_cm(options.performer, options.seed);
  if (height_cm < 50 || height_cm > 250)
    throw Error("generate_motion: expected a height in [50, 250] cm, found " + number_text(height_cm));
  const double h = height_cm / 100;
  const gen::Style style = gen::performer_style(options.performer, options.seed, h);
  rig::Rng take_rng(options.seed, 0x54616b65ULL + std::uint64_t(options.category),
                    std::uint64_t(options.performer), std::uint64_t(options.take));

  gen::Clip clip;
  switch (options.category) {
    case Category::walking: clip = gen::walking(style, take_rng, options.seconds, options.fps); break;
    case Category::rom: clip = gen::rom(style, take_rng, options.seconds, options.fps); break;
    case Category::freestyle: clip = gen::freestyle(style, take_rng, options.seconds, options.fps); break;
    case Category::acting: clip = gen::acting(style, take_rng, options.seconds, options.fps); break;
  }
  const Pose offsets = canonical_rest_offsets(height_cm);
  rig::settle_pelvis_heights(clip.controls, clip.nominal_z, offsets, options.fps);

  Motion m;
  m.name = motion_id(options.performer, options.category, options.take);
  m.fps = options.fps;
  m.frames.reserve(clip.controls.size());
  for (const auto& c : clip.controls) m.frames.push_back(rig::evaluate(c, offsets));
  return m;
}

}  // namespace ptnet
