// The move timeline of the non-walking generators (generate_script.hpp).
#include "generate_script.hpp"

#include <algorithm>
#include <cmath>

namespace ptnet::gen {

using Eigen::Vector2d;
using rig::deg;

double bump(double u, double dur) {
  if (u <= 0 || u >= dur) return 0;
  return 0.5 - 0.5 * std::cos(2 * rig::kPi * u / dur);
}

double hold(double u, double dur, double ramp) {
  if (u <= 0 || u >= dur) return 0;
  ramp = std::min(ramp, 0.5 * dur);
  return rig::smoothstep(u / ramp) * rig::smoothstep((dur - u) / ramp);
}

Vector2d stance_foot(const Vector2d& centre, double yaw, double half_width, int side) {
  const double s = side == 0 ? 1.0 : -1.0;
  return centre + half_width * s * Vector2d(-std::sin(yaw), std::cos(yaw));
}

Script::Script(const Style& style, rig::Rng& r, double secs, double f)
    : st(style), rng(r), h(style.height_m), fps(f), seconds(secs) {
  frames = std::max(1, int(std::lround(seconds * fps)));
  for (auto* ch : {&drop, &back, &shift, &twist, &pelvis_pitch, &trunk_pitch, &trunk_roll, &trunk_yaw,
                   &head_pitch, &head_yaw, &heel[0], &heel[1]})
    ch->assign(frames, 0.0);
  arm[0].assign(frames, rig::Arm{});
  arm[1].assign(frames, rig::Arm{});
  // Start standing, feet about hip width apart, near the mat centre, facing
  // along x either way.
  const double yaw = rng.chance(0.5) ? 0.0 : rig::kPi;
  const Vector2d c(rng.uniform(-0.1, 0.1), rng.uniform(-0.03, 0.03));
  const double hw = rng.uniform(0.045, 0.06) * h;
  for (int s = 0; s < 2; ++s) {
    Plant p;
    p.xy = stance_foot(c, yaw, hw, s);
    p.yaw = yaw + (s == 0 ? 1 : -1) * st.toe_out;
    feet[s].plants.push_back(p);
  }
  t = rng.uniform(0.2, 0.6);
}

int Script::first_frame(double t0) const { return std::max(0, int(std::ceil(t0 * fps - 1e-9))); }

double Script::facing() const {
  const double a = feet[0].plants.back().yaw, b = feet[1].plants.back().yaw;
  return std::atan2(std::sin(a) + std::sin(b), std::cos(a) + std::cos(b));
}

namespace {
constexpr double kFootprintHalfLength = 0.76;  // m: footprints (heel to toe tip) kept on the
constexpr double kFootprintHalfWidth = 0.25;   // 1.6 m x 0.56 m mat, with a small margin

// Shifts a flat footprint (ankle xy, heading yaw) so heel and toe tip are on the mat.
Vector2d onto_mat(Vector2d xy, double yaw, double h) {
  const Vector2d fwd(std::cos(yaw), std::sin(yaw));
  const Vector2d heel = xy + rig::kHeelPoint.x() * h * fwd, tip = xy + rig::kToeTipPoint.x() * h * fwd;
  const Vector2d lo = heel.cwiseMin(tip), hi = heel.cwiseMax(tip);
  const Vector2d limit(kFootprintHalfLength, kFootprintHalfWidth);
  for (int k = 0; k < 2; ++k) {
    if (hi[k] > limit[k]) xy[k] -= hi[k] - limit[k];
    if (lo[k] < -limit[k]) xy[k] += -limit[k] - lo[k];
  }
  return xy;
}
}  // namespace

void Script::step(int side, double t0, double dur, const Vector2d& target, double yaw, double clearance) {
  const Vector2d xy = onto_mat(target, yaw, h);
  Plant& last = feet[side].plants.back();
  last.leave_pitch = -deg(14);
  last.rise = std::min(0.25, 0.5 * dur);
  Plant p;
  p.lift = t0;
  p.land = t0 + dur;
  p.xy = xy;
  p.yaw = yaw;
  p.land_pitch = deg(5);
  p.rocker = std::min(0.15, 0.3 * dur);
  p.clearance = clearance >= 0 ? clearance : 0.035 * h;
  feet[side].plants.push_back(p);
}

double Script::move_to(double t0, const Vector2d& centre_xy, double yaw, double hw, double step_dur, int lead) {
  if (lead < 0) {
    // Lead with the foot on the side we are going to.
    const Vector2d d = centre_xy - centre();
    const double left = -std::sin(facing()) * d.x() + std::cos(facing()) * d.y();
    lead = std::abs(left) > 0.02 ? (left > 0 ? 0 : 1) : rng.integer(0, 1);
  }
  const double gap = 0.6 * step_dur;  // weight transfer between the steps
  for (int k = 0; k < 2; ++k) {
    const int s = k == 0 ? lead : 1 - lead;
    step(s, t0 + k * (step_dur + gap), step_dur, stance_foot(centre_xy, yaw, hw, s),
         yaw + (s == 0 ? 1 : -1) * st.toe_out);
  }
  return t0 + 2 * step_dur + gap;
}

Clip Script::finish() const {
  Clip clip;
  clip.h = h;
  clip.fps = fps;
  clip.frames = frames;
  const double hip_z = h * anthropometry::kDrillisContini.hip;
  const double ankle_z = h * anthropometry::kDrillisContini.ankle;
  for (int f = 0; f < frames; ++f) {
    const double t = f / fps;
    rig::Controls c;
    double swing[2];
    for (int s = 0; s < 2; ++s) {
      c.foot[s] = feet[s].at(t, h, heel[s][f]);
      swing[s] = feet[s].swing_activity(t, 0.25);
    }
    // Weight: where the moves put it, but all on the other foot while one swings.
    double w = std::clamp(0.5 + shift[f], 0.08, 0.92);
    w = w * (1 - swing[0]) + 0.1 * swing[0];
    w = w * (1 - swing[1]) + 0.9 * swing[1];
    const Vector2d al = c.foot[0].ankle.head<2>(), ar = c.foot[1].ankle.head<2>();
    const Vector2d fl = c.foot[0].rotation.col(0).head<2>(), fr = c.foot[1].rotation.col(0).head<2>();
    const double yaw = std::atan2(fl.y() + fr.y(), fl.x() + fr.x());
    const Vector2d fwd(std::cos(yaw), std::sin(yaw));
    const Vector2d xy = ar + w * (al - ar) - back[f] * fwd;
    c.pelvis = {xy.x(), xy.y(), hip_z};
    c.yaw = yaw + twist[f];
    c.pitch = deg(3) + pelvis_pitch[f];
    c.roll = deg(3) * (swing[0] - swing[1]);
    c.trunk_pitch = st.trunk_lean + trunk_pitch[f];
    c.trunk_roll = trunk_roll[f];
    c.trunk_yaw = trunk_yaw[f] - 0.5 * twist[f];
    c.head_pitch = st.head_pitch - 0.5 * st.trunk_lean + head_pitch[f];
    c.head_yaw = head_yaw[f];
    // Arms: relaxed, swinging a little with the legs, plus the moves.
    const double sep = std::clamp(fwd.dot(al - ar) / (0.4 * h), -1.0, 1.0);
    for (int s = 0; s < 2; ++s) {
      const rig::Arm& a = arm[s][f];
      c.arm[s].flex = 0.5 * st.arm_swing * (s == 0 ? -sep : sep) + a.flex;
      c.arm[s].abd = deg(6) + a.abd;
      c.arm[s].horiz = a.horiz;
      c.arm[s].elbow = st.elbow + a.elbow;
    }
    const double rise_l = std::max(0.0, c.foot[0].ankle.z() - ankle_z);
    const double rise_r = std::max(0.0, c.foot[1].ankle.z() - ankle_z);
    clip.controls.push_back(c);
    clip.nominal_z.push_back(hip_z - st.knee_soft * h - drop[f] + w * rise_l + (1 - w) * rise_r);
  }
  // The body's weight moves smoothly: two passes of a +/- 0.12 s box filter
  // on the pelvis' horizontal path.
  const int r = std::max(1, int(std::lround(0.12 * fps)));
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Vector2d> xy(frames);
    for (int f = 0; f < frames; ++f) xy[f] = clip.controls[f].pelvis.head<2>();
    for (int f = 0; f < frames; ++f) {
      Vector2d sum = Vector2d::Zero();
      for (int g = f - r; g <= f + r; ++g) sum += xy[std::clamp(g, 0, frames - 1)];
      clip.controls[f].pelvis.head<2>() = sum / (2 * r + 1);
    }
  }
  return clip;
}

}  // namespace ptnet::gen
