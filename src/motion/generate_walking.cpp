// Procedural walking: paces back and forth along x on a 1.6 m x 0.56 m mat,
// turning at its ends in two 90-degree step turns, so a fixed mat senses
// every frame.
//
// Gait timing (Winter; docs/anthropometry.md): a step lasts T = 1 /
// cadence; each foot is in stance 1.2 T (60 % of the 2 T cycle) and swings
// 0.8 T, so each transition has 0.2 T of double support (10 % of the cycle).
// A stance starts with the heel (toes up, rolling down about the heel during
// loading), stays flat, then rises onto the toe tip before toe-off.
// Footprints are fixed while on the ground, so stance feet never slide; the
// pelvis follows a smooth path through the footprints (over the stance foot at
// mid-stance), highest at mid-stance and lowest in double support.
#include <algorithm>
#include <cmath>

#include "generate_internal.hpp"

namespace ptnet::gen {

using Eigen::Vector2d;
using Eigen::Vector3d;
using rig::deg;

namespace {

constexpr double kMatHalfLength = 0.78;  // m: feet (heel to toe tip) stay within +/- this x
constexpr double kStanceFraction = 1.2;  // stance duration / step time (60 % of the cycle)
constexpr double kSwingFraction = 0.8;   // swing duration / step time

Vector2d heading(double yaw) { return {std::cos(yaw), std::sin(yaw)}; }
Vector2d rotate(double yaw, const Vector2d& v) {
  return {std::cos(yaw) * v.x() - std::sin(yaw) * v.y(), std::sin(yaw) * v.x() + std::cos(yaw) * v.y()};
}

}  // namespace

// Upper body and pelvis orientation from where the feet are: pelvis turns
// with the forward leg, the chest counter-rotates, and each arm swings
// opposite to its leg. `swing` [2] = swing activity of each foot.
void walking_upper_body(const Style& st, double h, double step_len, rig::Controls& c, double base_yaw,
                        const double swing[2], double arm_gain) {
  const Vector2d fwd = heading(base_yaw);
  const double sep =
      std::clamp(fwd.dot(c.foot[0].ankle.head<2>() - c.foot[1].ankle.head<2>()) / step_len, -1.3, 1.3);
  c.yaw = base_yaw - deg(4) * sep;
  c.roll = deg(3) * (swing[0] - swing[1]);
  c.pitch = deg(4);
  c.trunk_pitch = st.trunk_lean;
  c.trunk_yaw = deg(7) * sep;  // chest turns back against the pelvis
  c.head_pitch = st.head_pitch - 0.5 * st.trunk_lean;
  c.head_yaw = -0.4 * deg(3) * sep;
  for (int s = 0; s < 2; ++s) {
    const double flex = arm_gain * st.arm_swing * (s == 0 ? -sep : sep);
    c.arm[s].flex = flex;
    c.arm[s].abd = deg(7);
    c.arm[s].elbow = st.elbow + 0.6 * std::max(flex, 0.0);
  }
}

namespace {

// One take's walk: the style varied, step sizes, and the footprints and
// pelvis path that the frames are evaluated from.
struct WalkPlan {
  Style st;
  double h = 0, step_time = 0, step_len = 0, half_width = 0, sway = 0, toe_front = 0;
  FootTrack feet[2];
  rig::Spline pelvis;  // (x, y, yaw)
};

// Per-take variation around the performer's style (the first draws of `rng`).
WalkPlan vary(const Style& style, rig::Rng& rng) {
  WalkPlan w;
  Style& st = w.st;
  st = style;
  st.heel_strike *= rng.uniform(0.85, 1.15);
  st.toe_off *= rng.uniform(0.9, 1.1);
  st.trunk_lean += deg(rng.uniform(-1.5, 1.5));
  st.arm_swing *= rng.uniform(0.8, 1.25);
  w.h = st.height_m;
  w.step_time = 1 / (st.cadence * rng.uniform(0.97, 1.03));
  w.step_len = 0.5 * st.stride * w.h * rng.uniform(0.95, 1.04);
  w.half_width = 0.5 * st.step_width * w.h;
  w.sway = st.sway * w.h;
  w.toe_front = rig::kToeTipPoint.x() * w.h;
  return w;
}

Plant footprint(const WalkPlan& w, int s, const Vector2d& centre, double heading_yaw) {
  const double sgn = s == 0 ? 1.0 : -1.0;
  Plant p;
  p.xy = centre + rotate(heading_yaw, {0, sgn * w.half_width});
  p.yaw = heading_yaw + sgn * w.st.toe_out;
  return p;
}

// The steps: start near one end of the mat, facing the other; full steps
// while they fit, one shortened step up to the end, a two-step turn; until
// `seconds` are covered.
void plan_steps(WalkPlan& w, rig::Rng& rng, double seconds) {
  const Style& st = w.st;
  const double h = w.h, step_time = w.step_time, step_len = w.step_len;
  double yaw = rng.chance(0.5) ? 0.0 : rig::kPi;
  Vector2d c(-std::cos(yaw) * rng.uniform(0.3, 0.45), rng.uniform(-0.04, 0.04));
  int side = rng.chance(0.5) ? 0 : 1;  // first swing foot, 0 = left
  // Quiet standing before the first step: feet under the hip joints (+/- 0.0475 H;
  // preferred stance width ~17 cm between heel centres, McIlroy & Maki 1997),
  // wider than the walking step width.
  for (int s = 0; s < 2; ++s) {
    Plant p = footprint(w, s, c, yaw);
    p.xy = c + rotate(yaw, {0, (s == 0 ? 1.0 : -1.0) * 0.0475 * h});
    w.feet[s].plants.push_back(p);
  }
  w.pelvis.add(0, {c.x(), c.y(), yaw});
  double lift = rng.uniform(0.3, 0.6);
  {
    const double sgn = side == 0 ? -1.0 : 1.0;  // weight onto the stance foot first
    const Vector2d p = c + rotate(yaw, {0, sgn * w.sway});
    w.pelvis.add(lift + 0.4 * step_time, {p.x(), p.y(), yaw});
  }
  int turn_left = 0, turn_dir = 1;
  bool after_turn = false;  // the first step out of a turn (or from standing) is short
  double unwrapped = yaw;
  for (int k = 0; lift < seconds + 2 * step_time; ++k) {
    const Vector2d fwd = heading(yaw);
    bool turning = false;
    if (turn_left > 0) {
      turning = true;
      c += 0.02 * h * fwd;
      yaw += turn_dir * rig::kPi / 2;
      unwrapped += turn_dir * rig::kPi / 2;
      --turn_left;
      after_turn = true;
    } else {
      // Full steps while they fit on the mat, then one shortened step up to
      // its end (unless tiny), then turn.
      const double reach = fwd.x() > 0 ? (kMatHalfLength - w.toe_front) - c.x()
                                       : c.x() - (-kMatHalfLength + w.toe_front);
      const double len = std::min(k == 0 || after_turn ? 0.55 * step_len : step_len, reach);
      if (k > 0 && len < 0.4 * step_len) {
        // Step turn: open towards the stepping foot, 2 x 90 degrees.
        turning = true;
        turn_dir = side == 0 ? 1 : -1;
        c += 0.02 * h * fwd;
        yaw += turn_dir * rig::kPi / 2;
        unwrapped += turn_dir * rig::kPi / 2;
        turn_left = 1;
      } else {
        c += std::max(len, 0.0) * fwd;
        after_turn = false;
        c.y() *= 0.6;  // drift back to the mat's centre line
      }
    }
    yaw = rig::wrap_angle(yaw);
    Plant p = footprint(w, side, c, yaw);
    p.lift = lift;
    p.land = lift + kSwingFraction * step_time;
    p.land_pitch = turning ? 0.4 * st.heel_strike : st.heel_strike;
    p.rocker = 0.15 * kStanceFraction * step_time;
    p.clearance = 0.02 * h;
    p.rise = 0.5 * kStanceFraction * step_time;
    Plant& before = w.feet[side].plants.back();
    before.leave_pitch = turning ? 0.5 * st.toe_off : st.toe_off;
    before.rise = p.rise;
    w.feet[side].plants.push_back(p);

    const double sgn = side == 0 ? 1.0 : -1.0;
    const Vector2d q = c + rotate(yaw, {0, sgn * w.sway});
    w.pelvis.add(p.land + 0.6 * step_time, {q.x(), q.y(), unwrapped});
    lift = p.land + (kStanceFraction - 1) * step_time;  // double support
    side = 1 - side;
  }
}

// How far the pelvis sinks below its mid-stance height, m, given each
// foot's swing activity (FootTrack::swing_activity, 1 while swinging). It
// rides the planted legs' arcs (compass gait: a leg of length L whose ankle
// lies d ahead of or behind the pelvis along the heading holds it
// L - sqrt(L^2 - d^2) lower; the lowest over the planted feet), flattened by
// the stance knee and the foot's rockers to kArcShare of that. kArcShare is
// measured (docs/motion-generate.md): a treadmill walk's pelvis rises and
// falls 4.1 cm at 0.65 m steps, where the arc of its 0.87 m legs gives 6.4 cm.
// (rig::settle_pelvis_heights still caps the result at the height the real
// legs reach, rig::max_pelvis_z: this is the target below that limit.)
double pelvis_sink(const WalkPlan& w, const rig::Controls& c, const double swing[2], double yaw) {
  constexpr double kArcShare = 0.64;
  const auto& p = anthropometry::kDrillisContini;
  const double leg = (p.hip - p.ankle) * w.h;
  const Vector2d ahead = heading(yaw);
  double sink = 0;
  for (int s = 0; s < 2; ++s) {
    if (swing[s] >= 0.5) continue;  // a swinging foot holds nothing up
    const double d = std::min(std::abs(ahead.dot(c.foot[s].ankle.head<2>() - c.pelvis.head<2>())), 0.9 * leg);
    sink = std::max(sink, leg - std::sqrt(leg * leg - d * d));
  }
  return kArcShare * sink;
}

// The frames: feet on their tracks, pelvis on its path, the upper body from both.
Clip render(const WalkPlan& w, double seconds, double fps) {
  const Style& st = w.st;
  const double h = w.h;
  Clip clip;
  clip.h = h;
  clip.fps = fps;
  clip.frames = std::max(1, int(std::lround(seconds * fps)));
  const double hip_z = h * anthropometry::kDrillisContini.hip;
  for (int f = 0; f < clip.frames; ++f) {
    const double t = f / fps;
    rig::Controls c;
    double swing[2];
    for (int s = 0; s < 2; ++s) {
      c.foot[s] = w.feet[s].at(t, h);
      swing[s] = w.feet[s].swing_activity(t, 0.05);
    }
    const Vector3d pv = w.pelvis(t);
    c.pelvis = {pv.x(), pv.y(), hip_z};
    walking_upper_body(st, h, w.step_len, c, pv.z(), swing, 1.0);
    clip.controls.push_back(c);
    // stance knee ~15 deg at mid-stance, lower between
    clip.nominal_z.push_back(hip_z - (st.knee_soft + 0.015) * h - pelvis_sink(w, c, swing, pv.z()));
  }
  return clip;
}

}  // namespace

Clip walking(const Style& style, rig::Rng& rng, double seconds, double fps) {
  WalkPlan w = vary(style, rng);
  plan_steps(w, rng, seconds);
  return render(w, seconds, fps);
}

}  // namespace ptnet::gen
