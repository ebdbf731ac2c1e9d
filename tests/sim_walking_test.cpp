// Walking on the simulator (issue 3): the feet alternate, each step lands on
// the heel before the forefoot, the centre of pressure rolls from heel to toe
// in single stance, the vertical force peaks at 1.0-1.5 x body weight, and a
// taller body leaves longer footprints and longer strides. On the procedural
// walk (always) and on the real walking clips of ../shared/mocap (skipped
// when absent).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "core/anthropometry.hpp"
#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "sim_gait_util.hpp"

namespace ptnet {
namespace {

using test::Stance;

constexpr double kG = anthropometry::kGravity;

Motion procedural_walk(int performer, double seconds, double height_cm) {
  GenerateOptions g;
  g.category = Category::walking;
  g.performer = performer;
  g.seconds = seconds;
  return retarget(generate_motion(g), height_cm);
}

struct WalkRun {
  PressureSequence seq;
  std::vector<FrameTrace> trace;
  double bw = 0;  // body weight (N)
};

WalkRun run(const Motion& m, const BodySpec& spec, SimOptions o = {}) {
  const Body body(spec);
  WalkRun r;
  o.sensor = ideal_sensor();
  r.seq = simulate(m, body, o, &r.trace);
  r.bw = spec.weight_kg * kG;
  return r;
}

// Stances (a foot carrying > 3 % of body weight) after the standing start
// (the first 0.6 s) and not cut by the end of the clip.
std::vector<Stance> steps(const WalkRun& r) {
  std::vector<Stance> out;
  for (const Stance& s : test::stances(r.trace, 0.03 * r.bw))
    if (s.first > 18 && s.last + 1 < int(r.trace.size())) out.push_back(s);
  return out;
}

int first_frame(const WalkRun& r, const Stance& s, bool heel) {
  for (int t = s.first; t <= s.last; ++t) {
    const FootLoad& f = r.trace[t].foot[s.side];
    if ((heel ? f.heel_n : f.forefoot_n) > 0) return t;
  }
  return 1 << 30;
}

// Frames of stance s in which the other foot carries nothing.
std::vector<int> single_support(const WalkRun& r, const Stance& s) {
  std::vector<int> out;
  for (int t = s.first; t <= s.last; ++t)
    if (r.trace[t].foot[1 - s.side].force_n == 0) out.push_back(t);
  return out;
}

const BodySpec kBody{"b", Sex::male, 175, 72, "retargeted"};

TEST(SimWalking, ProceduralFeetAlternate) {
  for (int performer : {1, 2, 3}) {
    const WalkRun r = run(procedural_walk(performer, 12, kBody.height_cm), kBody);
    const auto st = steps(r);
    ASSERT_GE(st.size(), 14u) << "performer " << performer;
    for (std::size_t k = 1; k < st.size(); ++k)
      EXPECT_NE(st[k].side, st[k - 1].side) << "performer " << performer << " steps at frames " << st[k - 1].first
                                            << " and " << st[k].first;
    // Double support is brief: never two stances of the same foot overlapping,
    // and some single support in every step.
    for (const Stance& s : st) EXPECT_GE(single_support(r, s).size(), 3u) << "step at " << s.first;
  }
}

TEST(SimWalking, ProceduralHeelStrikesBeforeForefoot) {
  for (int performer : {1, 2, 3}) {
    const WalkRun r = run(procedural_walk(performer, 12, kBody.height_cm), kBody);
    for (const Stance& s : steps(r)) {
      const int heel = first_frame(r, s, true), fore = first_frame(r, s, false);
      EXPECT_LT(heel, fore) << "performer " << performer << " step at frame " << s.first;
      // The step begins on the heel alone: the forefoot carries nothing yet.
      EXPECT_EQ(r.trace[s.first].foot[s.side].forefoot_n, 0.0) << "step at frame " << s.first;
    }
  }
}

TEST(SimWalking, ProceduralCentreOfPressureRollsHeelToToe) {
  const double foot_cells = 0.152 * kBody.height_cm / 100 / 0.02;
  for (int performer : {1, 2, 3}) {
    const WalkRun r = run(procedural_walk(performer, 12, kBody.height_cm), kBody);
    std::vector<double> single_gain;
    for (const Stance& s : steps(r)) {
      // A step starts on the heel and leaves from the forefoot and toes.
      EXPECT_LT(r.trace[s.first].foot[s.side].cop_u, 0.35) << "performer " << performer << " step at " << s.first;
      EXPECT_GT(r.trace[s.last].foot[s.side].cop_u, 0.65) << "performer " << performer << " step at " << s.first;
      // On the mat: the sensed centre of pressure travels along the foot.
      const Eigen::Vector2d a = test::cop_cells(r.seq, s.first), b = test::cop_cells(r.seq, s.last);
      EXPECT_GT((b - a).norm(), 0.4 * foot_cells) << "step at frame " << s.first;
      // In single stance it moves forward too (the body passes over the foot).
      const std::vector<int> ss = single_support(r, s);
      if (ss.size() >= 3)
        single_gain.push_back(r.trace[ss.back()].foot[s.side].cop_u - r.trace[ss.front()].foot[s.side].cop_u);
    }
    ASSERT_GE(single_gain.size(), 10u);
    std::sort(single_gain.begin(), single_gain.end());
    EXPECT_GT(single_gain[single_gain.size() / 2], 0.15) << "performer " << performer << ": median gain in single stance";
    EXPECT_GT(single_gain[single_gain.size() / 5], 0.0) << "performer " << performer << ": 20th percentile";
  }
}

TEST(SimWalking, ProceduralPeakForceIsOneToOneAndAHalfBodyWeights) {
  for (int performer : {1, 2, 3, 4}) {
    const WalkRun r = run(procedural_walk(performer, 12, kBody.height_cm), kBody);
    double peak = 0;
    for (int t = 0; t < r.seq.frames(); ++t) peak = std::max(peak, test::total_force_n(r.seq, t));
    EXPECT_GE(peak / r.bw, 1.0) << "performer " << performer;
    EXPECT_LE(peak / r.bw, 1.5) << "performer " << performer;
    // Wholly on the mat: the sensed force is the load of every frame.
    for (int t = 0; t < r.seq.frames(); ++t)
      ASSERT_NEAR(test::total_force_n(r.seq, t), r.trace[t].load_n, 0.01 * r.bw) << "frame " << t;
  }
}

// A clip played faster (clips_at_speeds, load_clip) is the same walk in less
// time: the same path in 1/s of the frames, and, simulated anew, the feet
// land harder (the vertical force follows the centre of mass's faster rise
// and fall), where a warped map would keep the slow walk's forces.
TEST(SimWalking, FasterPlaybackIsTheSamePathAndLandsHarder) {
  ClipSource clip;
  clip.procedural.category = Category::walking;
  clip.procedural.performer = 1;
  clip.procedural.seconds = 12;
  clip.meta.motion_id = "walk";
  const std::vector<ClipSource> at = clips_at_speeds({clip}, {0.8, 1.25});
  ASSERT_EQ(at.size(), 2u);
  EXPECT_EQ(at[0].meta.motion_id, "walk_x0.8");
  EXPECT_EQ(at[1].meta.motion_id, "walk_x1.25");
  const Motion slow = retarget(load_clip(at[0], kFps), kBody.height_cm);
  const Motion fast = retarget(load_clip(at[1], kFps), kBody.height_cm);
  EXPECT_NEAR(double(slow.size()) / fast.size(), 1.25 / 0.8, 0.01);
  const auto path = [](const Motion& m) {
    const Eigen::Vector3d d = m.frames.back()[kPelvis] - m.frames.front()[kPelvis];
    return std::hypot(d.x(), d.y());
  };
  EXPECT_NEAR(path(fast), path(slow), 0.02 * path(slow));
  const auto peak_bw = [](const Motion& m) {
    const WalkRun r = run(m, kBody);
    double peak = 0;
    for (int t = 0; t < r.seq.frames(); ++t) peak = std::max(peak, test::total_force_n(r.seq, t));
    return peak / r.bw;
  };
  const double p_slow = peak_bw(slow), p_fast = peak_bw(fast);
  EXPECT_GT(p_fast, p_slow + 0.05) << "peak force " << p_slow << " -> " << p_fast << " body weights";
}

TEST(SimWalking, ProceduralPressuresArePlausible) {
  // Per-frame peaks on 2 cm cells: barefoot walking peaks of 200-500 kPa on
  // fine plates average down over a 4 cm^2 cell (../shared/anthropometry.md).
  SimOptions o;  // default sensor: saturates at 600 kPa
  for (int performer : {1, 2, 3, 4}) {
    const Body body(kBody);
    const PressureSequence s = simulate(procedural_walk(performer, 12, kBody.height_cm), body, o);
    std::vector<float> peaks;
    for (int t = 0; t < s.frames(); ++t) peaks.push_back(*std::max_element(s.frame(t), s.frame(t) + s.mat.cells()));
    std::sort(peaks.begin(), peaks.end());
    const float p95 = peaks[peaks.size() * 95 / 100], top = peaks.back();
    EXPECT_GT(p95, 80.0f) << "performer " << performer;
    EXPECT_LT(p95, 400.0f) << "performer " << performer;
    EXPECT_LT(top, 550.0f) << "performer " << performer << ": no frame near saturation";
  }
}

// Left-only walk: the right leg lifted away, so every footprint is the left's.
Motion left_only(Motion m) {
  for (Pose& p : m.frames)
    for (int j : {kRightKnee, kRightAnkle, kRightToe}) p[j].z() += 1.0;
  return m;
}

struct Prints {
  double length_m = 0;  // median footprint length
  double stride_m = 0;  // longest distance between consecutive footprints
};

Prints left_prints(double height_cm, double weight_kg) {
  SimOptions o;
  o.mat = MatSpec{200, 60, 0.02};  // 4 m x 1.2 m: the whole walk is on it
  const BodySpec spec{"b", Sex::male, height_cm, weight_kg, "retargeted"};
  const WalkRun r = run(left_only(procedural_walk(1, 12, height_cm)), spec, o);
  std::vector<double> lengths;
  std::vector<Eigen::Vector2d> centres;
  // Stances: runs of frames with any pressure.
  for (int t = 0; t < r.seq.frames();) {
    if (test::total_force_n(r.seq, t) == 0) { ++t; continue; }
    int e = t;
    while (e + 1 < r.seq.frames() && test::total_force_n(r.seq, e + 1) > 0) ++e;
    const test::Footprint f = test::footprint(r.seq, t, e);
    if (t > 0 && e + 1 < r.seq.frames()) lengths.push_back(f.length_m);
    centres.push_back(f.centroid * 0.02);
    t = e + 1;
  }
  Prints p;
  EXPECT_GE(lengths.size(), 5u);
  if (lengths.empty()) return p;
  std::sort(lengths.begin(), lengths.end());
  p.length_m = lengths[lengths.size() / 2];
  for (std::size_t k = 1; k < centres.size(); ++k) p.stride_m = std::max(p.stride_m, (centres[k] - centres[k - 1]).norm());
  return p;
}

TEST(SimWalking, TallerBodyLongerFootprintsAndStrides) {
  const Prints a = left_prints(160, 62), b = left_prints(190, 82);
  // Footprint length follows foot length 0.152 H (within 10 %), and so height.
  EXPECT_NEAR(a.length_m / (0.152 * 1.60), 1.0, 0.10) << a.length_m;
  EXPECT_NEAR(b.length_m / (0.152 * 1.90), 1.0, 0.10) << b.length_m;
  EXPECT_NEAR((b.length_m / a.length_m) / (190.0 / 160.0), 1.0, 0.10);
  // Strides scale with leg length.
  EXPECT_GT(b.stride_m, a.stride_m * 1.1);
  // (Passes of a 1.6 m mat: a few full strides between turns.)
  EXPECT_NEAR(a.stride_m / 1.60, 0.6, 0.15);
  EXPECT_NEAR(b.stride_m / 1.90, 0.6, 0.15);
}

// ------------------------------------------------------- real walking clips

const std::string kMocap = PTNET_SHARED_MOCAP;

std::vector<ClipSource> mocap_walks() {
  std::vector<ClipSource> out;
  for (const ClipSource& c : clips_from_files({}, kMocap + "/clips.csv", {}))
    if (c.meta.category == "walking") out.push_back(c);
  return out;
}

TEST(SimWalking, RealClipsAlternateRollAndPeak) {
  if (!std::filesystem::exists(kMocap + "/clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  SimOptions o;
  o.placement = Placement::follow;  // the clips cross ~4 m: the mat follows the walker
  int checked_steps = 0, heel_first_all = 0;
  int left_ok = 0, left_n = 0, right_ok = 0, right_n = 0;
  for (const ClipSource& clip : mocap_walks()) {
    const Motion m = retarget(load_clip(clip, 30), kBody.height_cm);
    const WalkRun r = run(m, kBody, o);
    const std::string name = clip.meta.motion_id;
    const auto st = steps(r);
    ASSERT_GE(st.size(), 2u) << name;
    // Loaded stances (> 30 % body weight) alternate between the feet.
    const auto loaded = test::stances(r.trace, 0.3 * r.bw);
    int alternate = 0;
    for (std::size_t k = 1; k < loaded.size(); ++k) alternate += loaded[k].side != loaded[k - 1].side;
    EXPECT_GE(alternate, 0.75 * double(loaded.size() - 1)) << name << ": consecutive steps by different feet";
    // The left foot on the documented left side (cols < 14), the right on the
    // right: in each clip the left foot's stances lie left of the right
    // foot's (the mat centre follows a smoothed path, so a narrow step on a
    // bend can cross the centre line), and most frames over all clips are on
    // their side.
    double left_col = 0, right_col = 0;
    int left_here = 0, right_here = 0;
    for (int t = 0; t < r.seq.frames(); ++t) {
      const bool l = r.trace[t].foot[0].force_n > 0, rr = r.trace[t].foot[1].force_n > 0;
      if (l == rr || test::total_force_n(r.seq, t) == 0) continue;
      const double col = test::cop_cells(r.seq, t).y();
      if (l) ++left_n, ++left_here, left_col += col, left_ok += col < r.seq.mat.cols / 2.0;
      else ++right_n, ++right_here, right_col += col, right_ok += col >= r.seq.mat.cols / 2.0;
    }
    ASSERT_GT(left_here, 0) << name;
    ASSERT_GT(right_here, 0) << name;
    EXPECT_GT(right_col / right_here, left_col / left_here + 1.0) << name << ": mean centre-of-pressure column, right vs left";
    std::vector<double> gain;
    int heel_first = 0;
    for (const Stance& s : st) {
      ++checked_steps;
      heel_first += first_frame(r, s, true) <= first_frame(r, s, false);
      const std::vector<int> ss = single_support(r, s);
      if (ss.size() >= 4)
        gain.push_back(r.trace[ss.back()].foot[s.side].cop_u - r.trace[ss.front()].foot[s.side].cop_u);
    }
    heel_first_all += heel_first;
    if (!gain.empty()) {
      std::sort(gain.begin(), gain.end());
      EXPECT_GT(gain[gain.size() / 2], 0.1) << name << ": median heel-to-toe travel in single stance";
    }
    double peak = 0;
    for (const FrameTrace& f : r.trace) peak = std::max(peak, f.load_n);
    EXPECT_GE(peak / r.bw, 1.0) << name;
    EXPECT_LE(peak / r.bw, 1.5) << name;
  }
  EXPECT_GE(checked_steps, 6);
  EXPECT_GE(left_ok, 0.7 * left_n);
  EXPECT_GE(right_ok, 0.7 * right_n);
  // Most real steps land on the heel (some captures land flat-footed).
  EXPECT_GE(heel_first_all, 0.6 * checked_steps);
}

TEST(SimWalking, RealClipsTallerBodyLongerFootprints) {
  if (!std::filesystem::exists(kMocap + "/clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  // Footprint length at mid-stance (largest region), over every step of
  // every walking clip, on a 160 cm and a 190 cm body.
  std::vector<double> la, lb;
  for (const ClipSource& clip : mocap_walks()) {
    const Motion src = load_clip(clip, 30);
    SimOptions o;
    o.placement = Placement::follow;
    const WalkRun a = run(retarget(src, 160), {"a", Sex::male, 160, 62, "retargeted"}, o);
    const WalkRun b = run(retarget(src, 190), {"b", Sex::male, 190, 82, "retargeted"}, o);
    for (const Stance& s : test::stances(a.trace, 0.3 * a.bw))
      la.push_back(test::largest_region_length_m(a.seq, (s.first + s.last) / 2));
    for (const Stance& s : test::stances(b.trace, 0.3 * b.bw))
      lb.push_back(test::largest_region_length_m(b.seq, (s.first + s.last) / 2));
  }
  ASSERT_GE(la.size(), 6u);
  ASSERT_GE(lb.size(), 6u);
  std::sort(la.begin(), la.end());
  std::sort(lb.begin(), lb.end());
  const double ma = la[la.size() / 2], mb = lb[lb.size() / 2];
  EXPECT_GT(mb, ma);
  EXPECT_NEAR(ma / (0.152 * 1.60), 0.9, 0.25);
  EXPECT_NEAR(mb / (0.152 * 1.90), 0.9, 0.25);
}

// Frames with the body on the ground beside the mat read 0. The simulator
// takes shortcuts there (no rasterising when no surface can reach the mat)
// and on the mat (four samples at a time); with a trace it takes none, so
// the two must agree bit for bit. The mat is under the walk for its first
// half and 0.8-2.3 m beside it (moving away) for the second.
TEST(SimWalking, OffTheMatFramesReadZeroAndTheShortcutsChangeNothing) {
  const Motion m = procedural_walk(1, 12, kBody.height_cm);
  const Body body(kBody);
  const SimOptions o;
  MotionPlacement place = place_motion(m, o);
  const int T = m.size();
  for (int t = T / 2; t < T; ++t) place.centre[t] += place.left * (0.8 + 1.5 * (t - T / 2) / double(T));
  std::vector<FrameTrace> trace;
  const PressureSequence fast = simulate(m, body, o, place, nullptr), full = simulate(m, body, o, place, &trace);
  ASSERT_EQ(fast.kpa.size(), full.kpa.size());
  EXPECT_EQ(0, std::memcmp(fast.kpa.data(), full.kpa.data(), fast.kpa.size() * sizeof(float)));
  int off = 0, on = 0;
  for (int t = 0; t < fast.frames(); ++t) {
    const float* f = fast.frame(t);
    const bool zero = std::all_of(f, f + fast.mat.cells(), [](float v) { return v == 0; });
    const double carried = trace[t].foot[0].force_n + trace[t].foot[1].force_n + trace[t].other_n;
    if (zero && carried > 0.5 * kBody.weight_kg * kG) ++off;
    if (!zero) ++on;
  }
  EXPECT_GT(off, T / 3) << "the body stands beside the mat";
  EXPECT_GT(on, T / 3) << "and on it";
}

}  // namespace
}  // namespace ptnet
