// Internal: a timeline on which the non-walking generators (rom, freestyle,
// acting) place their moves: footsteps, and additive per-frame channels
// (pelvis drop, trunk bends, arm angles...) shaped by smooth envelopes, then
// turned into per-frame controls (generate_script.cpp).
#pragma once

#include <vector>

#include "generate_internal.hpp"

namespace ptnet::gen {

// 0 -> 1 -> 0 over [0, dur] (raised cosine).
double bump(double u, double dur);
// 0 -> 1 (rising over `ramp`), hold, -> 0 (falling over `ramp`) across [0, dur].
double hold(double u, double dur, double ramp);

struct Script {
  Script(const Style& style, rig::Rng& rng, double seconds, double fps);

  const Style& st;
  rig::Rng& rng;
  double h, fps, seconds;
  int frames;
  double t = 0;  // s, where the next move starts
  FootTrack feet[2];
  // Additive channels [F]: pelvis drop (m), pelvis back (m, along facing),
  // weight shift to the left (-0.5..0.5), pelvis twist, pelvis pitch, trunk
  // pitch / roll / yaw, head pitch / yaw (rad), heel pitch per foot (rad).
  std::vector<double> drop, back, shift, twist, pelvis_pitch, trunk_pitch, trunk_roll, trunk_yaw, head_pitch,
      head_yaw;
  std::vector<double> heel[2];
  std::vector<rig::Arm> arm[2];  // additive arm angles

  // Adds f(u) (u = seconds since t0) to `ch` for frames in [t0, t0 + dur].
  template <class F>
  void add(std::vector<double>& ch, double t0, double dur, F f) {
    for (int i = first_frame(t0); i < frames && i / fps <= t0 + dur; ++i) ch[i] += f(i / fps - t0);
  }
  template <class F>
  void add_arm(int side, double t0, double dur, F f) {  // f(u, Arm&) adds to the arm
    for (int i = first_frame(t0); i < frames && i / fps <= t0 + dur; ++i) f(i / fps - t0, arm[side][i]);
  }
  int first_frame(double t0) const;

  // Moves foot `side` to xy / yaw, swinging over [t0, t0 + dur].
  void step(int side, double t0, double dur, const Eigen::Vector2d& xy, double yaw, double clearance = -1);
  // Both feet to a stance of half-width `half_width` around `centre` facing
  // `yaw` (leading foot first), from t; returns the end time.
  double move_to(double t0, const Eigen::Vector2d& centre, double yaw, double half_width, double step_dur,
                 int lead = -1);
  Eigen::Vector2d foot_xy(int side) const { return feet[side].plants.back().xy; }
  Eigen::Vector2d centre() const { return 0.5 * (foot_xy(0) + foot_xy(1)); }
  double facing() const;  // mean heading of the feet, rad
  double half_width() const { return 0.5 * (foot_xy(0) - foot_xy(1)).norm(); }

  Clip finish() const;
};

// Position of a foot in a stance: `side` 0 left.
Eigen::Vector2d stance_foot(const Eigen::Vector2d& centre, double yaw, double half_width, int side);

}  // namespace ptnet::gen
