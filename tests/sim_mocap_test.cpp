// Every real clip of ../shared/mocap (clips.csv) on four bodies (issue 3):
// simulates without error into finite, non-negative, saturation-bounded
// maps; the walking clips peak at 1.0-1.5 x body weight; contact regions are
// foot-sized (a loaded foot's region at mid-stance is 0.6-1.2 foot lengths,
// and no region anywhere is longer than a foot and a half). Skipped when
// ../shared/mocap is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/anthropometry.hpp"
#include "ptnet/body.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "sim_gait_util.hpp"

namespace ptnet {
namespace {

const std::string kMocap = PTNET_SHARED_MOCAP;

const std::vector<BodySpec> kBodies = {
    {"f150", Sex::female, 150, 48, "retargeted"},
    {"f168", Sex::female, 168, 66, "retargeted"},
    {"m178", Sex::male, 178, 82, "retargeted"},
    {"m196", Sex::male, 196, 104, "retargeted"},
};

TEST(SimMocap, EveryClipOnFourBodies) {
  if (!std::filesystem::exists(kMocap + "/clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  const std::vector<ClipSource> clips = clips_from_files({}, kMocap + "/clips.csv", {});
  ASSERT_GE(clips.size(), 11u);
  std::vector<Body> bodies;
  for (const auto& b : kBodies) bodies.emplace_back(b);
  int walking = 0;
  for (const ClipSource& clip : clips) {
    const Motion source = load_clip(clip, 30);
    const std::string name = clip.meta.motion_id;
    const bool is_walk = clip.meta.category == "walking";
    walking += is_walk;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Motion m = retarget(source, kBodies[b].height_cm);
      const double bw = kBodies[b].weight_kg * anthropometry::kGravity;
      const double foot_m = 0.152 * kBodies[b].height_cm / 100;
      // Default options: a fixed mat, the default sensor.
      SimOptions o;
      o.seed = 3;
      const PressureSequence s = simulate(m, bodies[b], o);
      ASSERT_EQ(s.frames(), m.size()) << name;
      for (float v : s.kpa) {
        ASSERT_TRUE(std::isfinite(v)) << name;
        ASSERT_GE(v, 0.0f) << name;
        ASSERT_LE(v, float(o.sensor.saturation_kpa)) << name;
      }
      // Physics on an ideal sensor, the mat following the body.
      SimOptions f;
      f.placement = Placement::follow;
      f.sensor = ideal_sensor();
      std::vector<FrameTrace> tr;
      const PressureSequence p = simulate(m, bodies[b], f, &tr);
      int sensed = 0;
      for (int t = 0; t < p.frames(); ++t) {
        if (test::total_force_n(p, t) == 0) continue;
        ++sensed;
        if (t % 3 == 0)  // every 3rd frame keeps the test fast
          EXPECT_LE(test::largest_region_length_m(p, t), 1.5 * foot_m + 0.04)
              << name << " on " << kBodies[b].id << " frame " << t;
      }
      EXPECT_GT(sensed, p.frames() / 2) << name << " on " << kBodies[b].id;
      if (!is_walk) continue;
      double peak = 0;
      for (const FrameTrace& x : tr) peak = std::max(peak, x.load_n);
      EXPECT_GE(peak / bw, 1.0) << name << " on " << kBodies[b].id;
      EXPECT_LE(peak / bw, 1.5) << name << " on " << kBodies[b].id;
      // A foot flat on the ground in single stance leaves a foot-long print.
      int flat = 0;
      for (int t = 0; t < p.frames(); ++t) {
        for (int side = 0; side < 2; ++side) {
          const FootLoad& l = tr[t].foot[side];
          if (tr[t].foot[1 - side].force_n > 0 || tr[t].other_n > 0) continue;
          if (!(l.heel_n > 0.2 * l.force_n && l.forefoot_n > 0.2 * l.force_n)) continue;
          ++flat;
          const double len = test::largest_region_length_m(p, t);
          EXPECT_GE(len, 0.6 * foot_m) << name << " on " << kBodies[b].id << " frame " << t;
          EXPECT_LE(len, 1.2 * foot_m + 0.02) << name << " on " << kBodies[b].id << " frame " << t;
        }
      }
      EXPECT_GT(flat, 3) << name << " on " << kBodies[b].id;
    }
  }
  EXPECT_GE(walking, 4);
}

}  // namespace
}  // namespace ptnet
