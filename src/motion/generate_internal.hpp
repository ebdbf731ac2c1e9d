// Internal: what the procedural generators share: per-performer style, foot
// tracks (planted footprints joined by swings), and the category builders.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "ptnet/motion.hpp"
#include "rig.hpp"

namespace ptnet::gen {

// Per-performer style, drawn once per performer (deterministic in seed).
struct Style {
  double height_m = 1.7;
  double cadence = 1.8;        // steps/s (Winter: 100-120 steps/min at normal speed)
  double stride = 0.76;        // stride length / H (~0.8 H at normal speed)
  double step_width = 0.07;    // lateral distance between the ankles' paths / H
  double arm_swing = 0.3;      // rad, shoulder flexion amplitude in walking
  double trunk_lean = 0.05;    // rad, habitual forward lean
  double head_pitch = 0.0;     // rad
  double elbow = 0.25;         // rad, resting elbow flexion
  double knee_soft = 0.008;    // standing knee bend, pelvis lowered by this fraction of H
  double tempo = 1.0;          // > 1: slower movements in the non-walking categories
  double heel_strike = 0.25;   // rad, toes up at heel strike
  double toe_off = -0.6;       // rad, heel up at toe-off
  double sway = 0.018;         // pelvis lateral sway in walking / H
  double toe_out = 0.08;       // rad, feet turned out
};
Style performer_style(int performer, std::uint64_t seed, double height_m);

// One footprint: the foot swings from the previous plant during [lift, land]
// and then stands here until the next plant's lift.
struct Plant {
  double lift = -1e9, land = -1e9;  // s
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // flat-foot ankle position, m
  double yaw = 0;                   // rad
  double land_pitch = 0;            // rad, toes up on landing (rolls down over `rocker`)
  double rocker = 0.1;              // s
  double leave_pitch = 0;           // rad, heel up when leaving (rises over `rise`)
  double rise = 0.2;                // s
  double clearance = 0.03;          // m, extra ankle lift mid-swing towards this plant
};

struct FootTrack {
  std::vector<Plant> plants;  // sorted by time
  // Foot pose at t; `extra_pitch` is added during stance (toe raises, lunges).
  rig::FootPose at(double t, double h, double extra_pitch = 0) const;
  // 1 while swinging, ramping smoothly from `ramp` s before lift to `ramp` s after landing.
  double swing_activity(double t, double ramp) const;
};

struct Clip {
  double h = 1.7;
  double fps = kFps;
  int frames = 0;
  std::vector<rig::Controls> controls;  // [F], pelvis z nominal until settled
  std::vector<double> nominal_z;        // [F], m
};

Clip walking(const Style& style, rig::Rng& take_rng, double seconds, double fps);
Clip rom(const Style& style, rig::Rng& take_rng, double seconds, double fps);
Clip freestyle(const Style& style, rig::Rng& take_rng, double seconds, double fps);
Clip acting(const Style& style, rig::Rng& take_rng, double seconds, double fps);

}  // namespace ptnet::gen
