// The simulator against a real mat (issue 27, item 4): a quiet stance of a
// 62 kg body against the public Tekscan recording of ../shared/anthropometry.md
// ("One real recording to check against"), resampled to 2 cm cells: 92 cells
// above 0.5 kPa, mean over them 16.5 kPa, peak 70 kPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "ptnet/body.hpp"
#include "ptnet/sim.hpp"
#include "sim_poses.hpp"

namespace ptnet {
namespace {

struct Stance {
  int cells = 0;      // above 0.5 kPa
  double mean = 0;    // over those cells, kPa
  double peak = 0;    // kPa
};

Stance measure(const PressureSequence& s, int t) {
  Stance r;
  for (int i = 0; i < s.mat.cells(); ++i) {
    const double v = s.frame(t)[i];
    if (v > 0.5) {
      ++r.cells;
      r.mean += v;
    }
    r.peak = std::max(r.peak, v);
  }
  if (r.cells) r.mean /= r.cells;
  return r;
}

// The recording names no body but its weight; 170 cm gives 62 kg a BMI of
// 21.5, the middle of the normal range. The physics (an ideal sensor) and
// the default sensor (crosstalk, noise, 1 kPa threshold, ADC step) both.
TEST(SimQuietStance, A62KgStanceMatchesTheRealMat) {
  constexpr double kCells = 92, kMeanKpa = 16.5, kPeakKpa = 70;  // anthropometry.md, 2 cm cells
  for (bool ideal : {true, false})
    for (Sex sex : {Sex::female, Sex::male}) {
      const Body body(BodySpec{"b", sex, 170, 62, "retargeted"});
      SimOptions o;
      if (ideal) o.sensor = ideal_sensor();
      o.seed = 3;
      const PressureSequence s = simulate(test::still_motion(test::rest_pose(170), 30), body, o);
      const std::string what = std::string(sex_name(sex)) + (ideal ? ", ideal sensor" : ", default sensor");
      for (int t : {5, 15, 25}) {
        const Stance st = measure(s, t);
        EXPECT_NEAR(st.cells, kCells, 0.15 * kCells) << what << ": contact area (cells above 0.5 kPa)";
        EXPECT_NEAR(st.mean, kMeanKpa, 0.15 * kMeanKpa) << what << ": mean over those cells";
        EXPECT_NEAR(st.peak, kPeakKpa, 0.30 * kPeakKpa) << what << ": peak";
      }
    }
}

}  // namespace
}  // namespace ptnet
