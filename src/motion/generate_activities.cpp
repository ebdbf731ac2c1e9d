// Procedural rom (range of motion / exercise), freestyle (dance-like) and
// acting clips: each a seeded sequence of moves on a Script timeline, mostly
// in place (stepping moves head back towards the mat centre).
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "generate_script.hpp"

namespace ptnet::gen {

using Eigen::Vector2d;
using rig::deg;

namespace {

constexpr double kHome = 0.25;  // m: beyond this from the mat centre, steps head back

// A step target `dist` away in direction `dir` (rad, world), pulled back
// towards the origin when the stance centre has wandered.
Vector2d wander(const Script& s, double dist, double dir) {
  Vector2d d(std::cos(dir), std::sin(dir));
  const Vector2d c = s.centre();
  if (c.norm() > kHome) d = (0.3 * d - c.normalized()).normalized();
  Vector2d target = c + dist * d;
  target.y() = std::clamp(target.y(), -0.1, 0.1);  // the mat is 0.56 m wide
  return target;
}

// ------------------------------------------------------------------ rom moves

double squats(Script& s) {
  const int reps = s.rng.integer(2, 4);
  const double dur = s.rng.uniform(2.0, 2.8) * s.st.tempo;
  const double depth = s.rng.uniform(0.14, 0.24) * s.h;  // pelvis drop
  const double arms = deg(s.rng.uniform(50, 85));       // arms forward for balance
  const double t0 = s.t;
  const double total = reps * dur;
  auto rep = [=](double u) { return bump(std::fmod(u, dur), dur); };
  s.add(s.drop, t0, total, [=](double u) { return depth * rep(u); });
  s.add(s.back, t0, total, [=](double u) { return 0.45 * depth * rep(u); });
  s.add(s.trunk_pitch, t0, total, [=](double u) { return deg(28) * depth / (0.2 * s.h) * rep(u); });
  s.add(s.pelvis_pitch, t0, total, [=](double u) { return deg(14) * depth / (0.2 * s.h) * rep(u); });
  s.add(s.head_pitch, t0, total, [=](double u) { return -deg(20) * rep(u); });
  for (int a = 0; a < 2; ++a)
    s.add_arm(a, t0, total, [=](double u, rig::Arm& arm) { arm.flex += arms * rep(u); });
  return t0 + total;
}

double lunges(Script& s) {
  const int reps = s.rng.integer(1, 2);
  const double len = s.rng.uniform(0.30, 0.40) * s.h;
  const double depth = s.rng.uniform(0.12, 0.17) * s.h;
  double t = s.t;
  int side = s.rng.integer(0, 1);
  for (int r = 0; r < 2 * reps; ++r, side = 1 - side) {
    const double yaw = s.facing();
    const Vector2d fwd(std::cos(yaw), std::sin(yaw));
    const Vector2d home = s.foot_xy(side);
    const double home_yaw = s.feet[side].plants.back().yaw;
    const double step_dur = 0.55 * s.st.tempo;
    s.step(side, t, step_dur, home + len * fwd, home_yaw);
    const double down = t + step_dur + 0.15;
    const double dur = s.rng.uniform(1.6, 2.2) * s.st.tempo;
    s.add(s.drop, down, dur, [=](double u) { return depth * hold(u, dur, 0.6 * s.st.tempo); });
    s.add(s.heel[1 - side], down - 0.2, dur + 0.4,
          [=](double u) { return -deg(38) * hold(u, dur + 0.4, 0.45); });
    s.add(s.trunk_pitch, down, dur, [=](double u) { return -deg(4) * hold(u, dur, 0.6); });
    s.add(s.shift, down - 0.2, dur + 0.4,
          [=](double u) { return (side == 0 ? 0.12 : -0.12) * hold(u, dur + 0.4, 0.4); });
    t = down + dur + 0.2;
    s.step(side, t, step_dur, home, home_yaw);
    t += step_dur + 0.4;
  }
  return t;
}

double arm_circles(Script& s) {
  const double period = s.rng.uniform(1.0, 1.5) * s.st.tempo;
  const int cycles = s.rng.integer(3, 5);
  const double radius = deg(s.rng.uniform(15, 28));
  const double raise = 0.8 * s.st.tempo;
  const double total = 2 * raise + 2 * cycles * period;
  const double t0 = s.t;
  const bool forward_first = s.rng.chance(0.5);
  for (int a = 0; a < 2; ++a)
    s.add_arm(a, t0, total, [=](double u, rig::Arm& arm) {
      const double env = hold(u, total, raise);
      const double v = u - raise;
      double dir = (v < cycles * period) == forward_first ? 1 : -1;
      const double phase = 2 * rig::kPi * v / period;
      const double circle = (v > 0 && v < 2 * cycles * period) ? 1.0 : 0.0;
      const double fade = hold(v, 2 * cycles * period, 0.3 * period) * circle;
      arm.abd += env * deg(85) + fade * radius * std::cos(phase);
      arm.horiz += fade * dir * radius * std::sin(phase);
      arm.elbow -= env * deg(10);
    });
  return t0 + total;
}

double toe_raises(Script& s) {
  const int reps = s.rng.integer(3, 6);
  const double dur = s.rng.uniform(1.2, 1.8) * s.st.tempo;
  const double lift = -deg(s.rng.uniform(22, 34));
  const double t0 = s.t;
  for (int f = 0; f < 2; ++f)
    s.add(s.heel[f], t0, reps * dur, [=](double u) { return lift * bump(std::fmod(u, dur), dur); });
  s.add(s.trunk_pitch, t0, reps * dur, [=](double u) { return -deg(3) * bump(std::fmod(u, dur), dur); });
  return t0 + reps * dur;
}

double side_bends(Script& s) {
  const int reps = s.rng.integer(1, 3);
  const double dur = s.rng.uniform(2.2, 3.0) * s.st.tempo;
  const double bend = deg(s.rng.uniform(20, 32));
  double t = s.t;
  int dir = s.rng.chance(0.5) ? 1 : -1;  // +1: bend to the left
  for (int r = 0; r < 2 * reps; ++r, dir = -dir) {
    s.add(s.trunk_roll, t, dur, [=](double u) { return dir * bend * hold(u, dur, 0.45 * dur); });
    s.add(s.shift, t, dur, [=](double u) { return -dir * 0.12 * hold(u, dur, 0.45 * dur); });
    const int over = dir > 0 ? 1 : 0;  // the arm on the far side goes overhead
    s.add_arm(over, t, dur, [=](double u, rig::Arm& arm) {
      const double e = hold(u, dur, 0.45 * dur);
      arm.abd += deg(150) * e;
      arm.elbow += deg(20) * e;
    });
    s.add_arm(1 - over, t, dur, [=](double u, rig::Arm& arm) { arm.elbow += deg(30) * hold(u, dur, 0.45 * dur); });
    t += dur;
  }
  return t;
}

double forward_bend(Script& s, double depth_deg, double reach_arms) {
  const double dur = s.rng.uniform(2.4, 3.4) * s.st.tempo;
  const double bend = deg(depth_deg);
  const double t0 = s.t;
  auto e = [=](double u) { return hold(u, dur, 0.4 * dur); };
  s.add(s.trunk_pitch, t0, dur, [=](double u) { return 0.55 * bend * e(u); });
  s.add(s.pelvis_pitch, t0, dur, [=](double u) { return 0.45 * bend * e(u); });
  s.add(s.back, t0, dur, [=](double u) { return 0.07 * s.h * std::sin(bend) * e(u); });
  s.add(s.drop, t0, dur, [=](double u) { return 0.04 * s.h * e(u); });
  s.add(s.head_pitch, t0, dur, [=](double u) { return -0.3 * bend * e(u); });
  for (int a = 0; a < 2; ++a)
    s.add_arm(a, t0, dur, [=](double u, rig::Arm& arm) { arm.flex += reach_arms * e(u); });
  return t0 + dur;
}

double pause(Script& s, double lo, double hi) {
  const double dur = s.rng.uniform(lo, hi) * s.st.tempo;
  const double sway = s.rng.uniform(-0.08, 0.08);
  s.add(s.shift, s.t, dur, [=](double u) { return sway * hold(u, dur, 0.4 * dur); });
  return s.t + dur;
}

// ---------------------------------------------------------- freestyle moves

double side_step_touch(Script& s, double beat) {
  const int count = s.rng.integer(2, 4);
  double t = s.t;
  const double yaw = s.facing();
  const Vector2d left(-std::sin(yaw), std::cos(yaw));
  const double hw = s.half_width();
  int dir = s.rng.chance(0.5) ? 1 : -1;
  for (int k = 0; k < count; ++k, dir = -dir) {
    // Step out to the side and close; stay on the mat (|x| < 0.4, |y| < 0.08 m).
    const double dist = s.rng.uniform(0.07, 0.11) * s.h;
    Vector2d c = s.centre() + dist * dir * left;
    if (std::abs(c.x()) > 0.4 || std::abs(c.y()) > 0.08) {
      dir = -dir;
      c = s.centre() + dist * dir * left;
    }
    const int lead = dir > 0 ? 0 : 1;
    s.step(lead, t, 0.8 * beat, stance_foot(c, yaw, hw, lead), s.feet[lead].plants.back().yaw);
    s.step(1 - lead, t + beat, 0.8 * beat, stance_foot(c, yaw, hw, 1 - lead), s.feet[1 - lead].plants.back().yaw);
    for (int a = 0; a < 2; ++a)
      s.add_arm(a, t, 2 * beat, [=](double u, rig::Arm& arm) {
        arm.abd += deg(35) * bump(u, 2 * beat);
        arm.elbow += deg(50) * bump(u, 2 * beat);
      });
    s.add(s.trunk_roll, t, 2 * beat, [=](double u) { return -dir * deg(6) * bump(u, 2 * beat); });
    t += 2 * beat;
  }
  return t;
}

double hip_sway(Script& s, double beat) {
  const int beats = 2 * s.rng.integer(3, 5);
  const double amp = s.rng.uniform(0.25, 0.38);
  const double t0 = s.t, total = beats * beat;
  const double env_ramp = beat;
  s.add(s.shift, t0, total, [=](double u) {
    return amp * std::sin(rig::kPi * u / beat) * hold(u, total, env_ramp);
  });
  s.add(s.trunk_roll, t0, total, [=](double u) {
    return -deg(7) * std::sin(rig::kPi * u / beat) * hold(u, total, env_ramp);
  });
  s.add(s.twist, t0, total, [=](double u) {
    return deg(8) * std::sin(rig::kPi * u / beat + 0.8) * hold(u, total, env_ramp);
  });
  const double arm_amp = deg(s.rng.uniform(30, 60));
  for (int a = 0; a < 2; ++a)
    s.add_arm(a, t0, total, [=](double u, rig::Arm& arm) {
      const double e = hold(u, total, env_ramp);
      arm.elbow += deg(70) * e;
      arm.flex += e * (deg(20) + arm_amp * 0.5 * (1 + std::sin(rig::kPi * u / beat + (a ? rig::kPi : 0))));
    });
  return t0 + total;
}

double spin_turn(Script& s, double beat) {
  const int steps = s.rng.integer(2, 4);
  const double dir = s.rng.chance(0.5) ? 1 : -1;
  const double per = dir * deg(s.rng.uniform(60, 90));
  double t = s.t;
  double yaw = s.facing();
  const Vector2d c = s.centre();
  const double hw = s.half_width();
  int lead = dir > 0 ? 0 : 1;  // open towards the turn
  for (int k = 0; k < steps; ++k, lead = 1 - lead) {
    yaw += per;
    s.step(lead, t, 0.8 * beat, stance_foot(c, yaw, hw, lead), yaw + (lead == 0 ? 1 : -1) * s.st.toe_out);
    t += beat;
  }
  // Close the other foot.
  s.step(lead, t, 0.8 * beat, stance_foot(c, yaw, hw, lead), yaw + (lead == 0 ? 1 : -1) * s.st.toe_out);
  for (int a = 0; a < 2; ++a)
    s.add_arm(a, s.t, t + beat - s.t, [=, t0 = s.t, d = t + beat - s.t](double u, rig::Arm& arm) {
      arm.abd += deg(45) * hold(u, d, beat);
      arm.elbow += deg(40) * hold(u, d, beat);
    });
  return t + beat;
}

double rock_step(Script& s, double beat) {
  const int reps = s.rng.integer(1, 3);
  double t = s.t;
  int side = s.rng.integer(0, 1);
  for (int r = 0; r < reps; ++r, side = 1 - side) {
    const double yaw = s.facing();
    Vector2d fwd(std::cos(yaw), std::sin(yaw));
    const Vector2d home = s.foot_xy(side);
    const double home_yaw = s.feet[side].plants.back().yaw;
    double dist = s.rng.uniform(0.16, 0.24) * s.h;
    if (s.centre().dot(fwd) > 0.2) dist = -0.6 * dist;  // rock back instead
    s.step(side, t, 0.8 * beat, home + dist * fwd, home_yaw);
    s.add(s.shift, t + 0.8 * beat, beat, [=](double u) { return (side == 0 ? 0.3 : -0.3) * bump(u, beat); });
    s.add(s.drop, t + 0.8 * beat, beat, [=](double u) { return 0.03 * s.h * bump(u, beat); });
    s.step(side, t + 2 * beat, 0.8 * beat, home, home_yaw);
    t += 3 * beat;
  }
  return t;
}

double arm_wave(Script& s, double beat) {
  const int beats = 2 * s.rng.integer(2, 4);
  const double t0 = s.t, total = beats * beat;
  for (int a = 0; a < 2; ++a)
    s.add_arm(a, t0, total, [=](double u, rig::Arm& arm) {
      const double e = hold(u, total, beat);
      arm.abd += e * deg(140);
      arm.horiz += e * deg(25) * std::sin(rig::kPi * u / beat + a * rig::kPi);
      arm.elbow += e * deg(25);
    });
  s.add(s.trunk_roll, t0, total, [=](double u) { return deg(6) * std::sin(rig::kPi * u / beat) * hold(u, total, beat); });
  return t0 + total;
}

// ------------------------------------------------------------- acting moves

double shift_weight(Script& s) {
  const double dur = s.rng.uniform(2.0, 3.5) * s.st.tempo;
  const double amp = (s.rng.chance(0.5) ? 1 : -1) * s.rng.uniform(0.25, 0.38);
  s.add(s.shift, s.t, dur, [=](double u) { return amp * hold(u, dur, 0.6); });
  s.add(s.trunk_roll, s.t, dur, [=](double u) { return -amp * deg(6) * hold(u, dur, 0.6); });
  // The unloaded knee relaxes a little.
  s.add(s.drop, s.t, dur, [=](double u) { return 0.008 * s.h * hold(u, dur, 0.6); });
  return s.t + dur;
}

double turn_around(Script& s) {
  const double angle = (s.rng.chance(0.5) ? 1 : -1) * deg(s.rng.uniform(60, 180));
  const double yaw = s.facing() + angle;
  // At most 80 degrees per pair of steps: the feet never point opposite ways.
  const int steps = int(std::ceil(std::abs(angle) / deg(80)));
  double t = s.t;
  const double dur = 0.6 * s.st.tempo;
  const Vector2d c = s.centre();
  const double hw = std::clamp(s.half_width(), 0.04 * s.h, 0.065 * s.h);
  for (int k = 1; k <= steps; ++k) {
    const double y = s.facing() + (yaw - s.facing()) * 1.0 / (steps - k + 1);
    const Vector2d cc = c;  // turn on the spot
    t = s.move_to(t, cc, y, hw, dur, angle > 0 ? 0 : 1) + 0.1;
  }
  s.add(s.head_yaw, s.t, t - s.t, [=, d = t - s.t](double u) { return 0.3 * angle * bump(u, d); });
  return t;
}

double walk_steps(Script& s) {
  const double dir = s.facing() + deg(s.rng.uniform(-60, 60)) + (s.rng.chance(0.25) ? rig::kPi : 0);
  const int moves = s.rng.integer(1, 3);
  const double hw = std::clamp(s.half_width(), 0.04 * s.h, 0.065 * s.h);
  double t = s.t;
  for (int k = 0; k < moves; ++k) {
    const Vector2d target = wander(s, s.rng.uniform(0.12, 0.2) * s.h, dir);
    t = s.move_to(t, target, s.facing(), hw, 0.6 * s.st.tempo) + 0.15;
  }
  return t + 0.2;
}

double reach(Script& s) {
  const int side = s.rng.integer(0, 1);
  const double dur = s.rng.uniform(2.0, 3.2) * s.st.tempo;
  const int kind = s.rng.integer(0, 2);  // forward, up, to the side
  const double t0 = s.t;
  auto e = [=](double u) { return hold(u, dur, 0.35 * dur); };
  s.add_arm(side, t0, dur, [=](double u, rig::Arm& arm) {
    if (kind == 0) arm.flex += deg(95) * e(u);
    if (kind == 1) arm.flex += deg(160) * e(u);
    if (kind == 2) arm.abd += deg(95) * e(u);
    arm.elbow -= 0.8 * s.st.elbow * e(u);
  });
  const double sgn = side == 0 ? 1 : -1;
  if (kind == 0) s.add(s.trunk_pitch, t0, dur, [=](double u) { return deg(15) * e(u); });
  if (kind == 1) s.add(s.trunk_pitch, t0, dur, [=](double u) { return -deg(6) * e(u); });
  if (kind == 2) s.add(s.trunk_roll, t0, dur, [=](double u) { return sgn * deg(12) * e(u); });
  s.add(s.shift, t0, dur, [=](double u) { return sgn * 0.2 * e(u); });
  s.add(s.trunk_yaw, t0, dur, [=](double u) { return -sgn * deg(10) * e(u); });
  return t0 + dur;
}

double gesture(Script& s) {
  const double dur = s.rng.uniform(2.0, 4.0) * s.st.tempo;
  const double f1 = s.rng.uniform(0.6, 1.2), f2 = s.rng.uniform(0.7, 1.4);
  const double t0 = s.t;
  for (int a = 0; a < 2; ++a) {
    const double amp = s.rng.uniform(0.3, 1.0);
    s.add_arm(a, t0, dur, [=](double u, rig::Arm& arm) {
      const double e = hold(u, dur, 0.5);
      const double w = std::sin(2 * rig::kPi * (a ? f2 : f1) * u);
      arm.flex += e * amp * (deg(30) + deg(15) * w);
      arm.elbow += e * amp * (deg(70) + deg(20) * w);
      arm.horiz += e * amp * deg(10) * w;
    });
  }
  s.add(s.head_yaw, t0, dur, [=](double u) { return deg(15) * std::sin(2 * rig::kPi * 0.3 * u) * hold(u, dur, 0.5); });
  return t0 + dur;
}

double look_around(Script& s) {
  const double dur = s.rng.uniform(2.0, 3.0) * s.st.tempo;
  const double yaw = (s.rng.chance(0.5) ? 1 : -1) * deg(s.rng.uniform(30, 60));
  s.add(s.head_yaw, s.t, dur, [=](double u) { return yaw * hold(u, dur, 0.5); });
  s.add(s.trunk_yaw, s.t, dur, [=](double u) { return 0.4 * yaw * hold(u, dur, 0.6); });
  s.add(s.twist, s.t, dur, [=](double u) { return 0.15 * yaw * hold(u, dur, 0.6); });
  return s.t + dur;
}

// Runs moves drawn by `next` until the clip is full.
Clip run(Script& s, const std::function<double(Script&, int)>& next) {
  for (int i = 0; s.t < s.seconds; ++i) s.t = next(s, i);
  return s.finish();
}

// A shuffled order of `n` move kinds, re-shuffled when used up.
class Deck {
 public:
  Deck(int n, rig::Rng& rng) : n_(n), rng_(rng) {}
  int draw() {
    if (order_.empty()) {
      for (int i = 0; i < n_; ++i) order_.push_back(i);
      for (int i = n_ - 1; i > 0; --i) std::swap(order_[i], order_[rng_.integer(0, i)]);
    }
    const int v = order_.back();
    order_.pop_back();
    return v;
  }

 private:
  int n_;
  rig::Rng& rng_;
  std::vector<int> order_;
};

}  // namespace

Clip rom(const Style& style, rig::Rng& rng, double seconds, double fps) {
  Script s(style, rng, seconds, fps);
  Deck deck(6, rng);
  return run(s, [&](Script& sc, int i) {
    if (i % 2 == 1) return pause(sc, 0.5, 1.2);
    switch (deck.draw()) {
      case 0: return squats(sc);
      case 1: return lunges(sc);
      case 2: return arm_circles(sc);
      case 3: return toe_raises(sc);
      case 4: return side_bends(sc);
      default: return forward_bend(sc, sc.rng.uniform(55, 80), deg(70));
    }
  });
}

Clip freestyle(const Style& style, rig::Rng& rng, double seconds, double fps) {
  Script s(style, rng, seconds, fps);
  const double beat = 60.0 / (rng.uniform(96, 128) / style.tempo);
  // A knee bounce on every beat, all through.
  const double bounce = rng.uniform(0.008, 0.016) * s.h;
  s.add(s.drop, 0, seconds, [=](double u) { return bounce * (0.5 - 0.5 * std::cos(2 * rig::kPi * u / beat)); });
  Deck deck(5, rng);
  return run(s, [&](Script& sc, int) {
    switch (deck.draw()) {
      case 0: return side_step_touch(sc, beat);
      case 1: return hip_sway(sc, beat);
      case 2: return spin_turn(sc, beat);
      case 3: return rock_step(sc, beat);
      default: return arm_wave(sc, beat);
    }
  });
}

Clip acting(const Style& style, rig::Rng& rng, double seconds, double fps) {
  Script s(style, rng, seconds, fps);
  Deck deck(7, rng);
  return run(s, [&](Script& sc, int i) {
    if (i % 2 == 1) return pause(sc, 0.8, 2.0);
    switch (deck.draw()) {
      case 0: return shift_weight(sc);
      case 1: return turn_around(sc);
      case 2: return walk_steps(sc);
      case 3: return forward_bend(sc, sc.rng.uniform(40, 70), deg(80));
      case 4: return reach(sc);
      case 5: return gesture(sc);
      default: return look_around(sc);
    }
  });
}

}  // namespace ptnet::gen
