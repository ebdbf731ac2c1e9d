// Marker files (.trc) in: the parser, marker maps, gap filling, the joints
// from anatomical landmarks (Harrington hip centres, joint-centre
// midpoints), the static-trial calibration of missing markers, a treadmill's
// belt; then the real gait-lab trials of ../shared/real-gait (skipped when
// absent).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "motion/markers_internal.hpp"
#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/markers.hpp"
#include "motion_markers_util.hpp"

using namespace ptnet::testing;

TEST(Trc, ParsesHeaderNamesRowsAndBlankCells) {
  std::vector<std::vector<V>> frames = {{V(1, 2, 3), V(4, 5, 6)}, {V(7, 8, 9), V(NAN, NAN, NAN)}};
  std::string text = trc_text({"A", "B"}, frames, 100);
  // CRLF line ends read the same.
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (const std::string& t : {text, crlf}) {
    const ptnet::Trc trc = ptnet::parse_trc(t, "t.trc");
    ASSERT_EQ(trc.frames(), 2);
    EXPECT_EQ(trc.markers, (std::vector<std::string>{"A", "B"}));
    EXPECT_EQ(trc.rate_hz, 100);
    EXPECT_EQ(trc.metres_per_unit, 0.001);
    EXPECT_EQ(trc.at(1, 0), V(7, 8, 9));
    EXPECT_TRUE(std::isnan(trc.at(1, 1).x()));
    EXPECT_DOUBLE_EQ(trc.time_s[1], 0.01);
    EXPECT_EQ(trc.find("B"), 1);
    EXPECT_EQ(trc.find("C"), -1);
  }
}

TEST(Trc, EveryMalformedFixtureIsItsOwnOneLineError) {
  const std::string dir = std::string(PTNET_TEST_DATA) + "/malformed/";
  const std::pair<const char*, const char*> cases[] = {
      {"empty.trc", ":1: expected PathFileType (an OpenSim .trc file), found an empty file"},
      {"not_a_trc.trc", ":1: expected PathFileType (an OpenSim .trc file), found 'HIERARCHY'"},
      {"no_data_rate.trc", ":2: expected DataRate among the header's names, found none"},
      {"bad_units.trc", ":3: expected Units mm, cm or m, found 'furlong'"},
      {"no_marker_names.trc", ":4: expected Frame# and Time then the marker names, found 'Time\\x09A\\x09\\x09\\x09B'"},
      {"marker_count_mismatch.trc", ":4: expected 3 marker names (NumMarkers), found 2"},
      {"long_row.trc", ":7: expected at most 8 values (Frame#, Time, 2 markers x 3), found 9"},
      {"non_numeric_coordinate.trc", ":7: expected a coordinate of 'B', found 'abc'"},
      {"inf_coordinate.trc", ":7: expected a coordinate of 'A', found 'inf'"},
      {"partial_marker.trc", ":7: expected all three or none of 'A''s X Y Z, found 1 of them"},
      {"time_backwards.trc", ":8: expected a time after 0.01 s, found '0.000'"},
      {"truncated.trc", ": expected 5 frames (NumFrames), found 2 (a truncated file?)"},
      {"no_frames.trc", ": expected rows of Frame#, Time, X Y Z ..., found none"},
      {"rate_mismatch.trc", ":3: expected a DataRate the Time column agrees with (its steps are 0.1 s: 10 Hz), found 60"},
      {"header_value_count.trc", ":3: expected 5 values, one per name of line 2, found 4"},
  };
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.path().extension() == ".trc";
  EXPECT_EQ(files, std::size(cases)) << "every .trc fixture has its expected message here";
  for (const auto& [file, message] : cases) {
    SCOPED_TRACE(file);
    try {
      ptnet::read_trc(dir + file);
      ADD_FAILURE() << "no error";
    } catch (const ptnet::Error& e) {
      EXPECT_EQ(std::string(e.what()), dir + file + message);
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
}

TEST(MarkerMap, FileFormatShippedMapsAndErrors) {
  const ptnet::MarkerMap m = ptnet::parse_marker_map("# a lab\nmap = mine\nr_asis = RA R_ASIS  # right\nl_asis=LA\n", "m.map");
  EXPECT_EQ(m.name, "mine");
  ASSERT_EQ(m.entries.size(), 2u);
  EXPECT_EQ(m.entries[0].names, (std::vector<std::string>{"RA", "R_ASIS"}));
  EXPECT_EQ(ptnet::marker_map_names(), (std::vector<std::string>{"common", "delaware", "plugin-gait"}));
  for (const std::string& n : ptnet::marker_map_names()) EXPECT_EQ(ptnet::marker_map(n).name, n);
  try {
    ptnet::parse_marker_map("r_asis = RA\nr_hip = RHIP\n", "m.map");
    ADD_FAILURE();
  } catch (const ptnet::Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("m.map:2: expected a landmark (r_asis, l_asis, ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("found 'r_hip'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ptnet::parse_marker_map("r_asis = A\nr_asis = B\n", "m.map"), ptnet::Error);
  EXPECT_THROW(ptnet::parse_marker_map("r_asis\n", "m.map"), ptnet::Error);
  EXPECT_THROW(ptnet::marker_map("no_such.map"), ptnet::Error);
}

TEST(Markers, HipCentresFollowHarrington2007) {
  const Standing s = standing();
  const ptnet::Trc trc = ptnet::parse_trc(trc_text(s.names, moved(s, 3, 100), 100), "t.trc");
  ptnet::MarkerReport report;
  const ptnet::Motion m = ptnet::motion_from_trc(trc, keep_rate(), &report);
  EXPECT_EQ(report.map, "delaware");
  EXPECT_EQ(report.up_axis, ptnet::UpAxis::y);
  // Lab (x, y, z) mm -> world (z, x, y) m. Pelvis frame of frame 0: origin
  // the ASIS midpoint (0.12, 0, 1.0) in lab m, anterior +X, right +Z.
  const double pw = 0.24, pd = 0.22;  // inter-ASIS; ASIS midpoint to the sacral marker
  const V hip_r_lab(0.12 - 0.24 * pd - 0.0099, 1.0 - 0.30 * pw - 0.0109, 0.33 * pw + 0.0073);
  const V hip_l_lab(hip_r_lab.x(), hip_r_lab.y(), -hip_r_lab.z());
  auto world = [](const V& l) { return V(l.z(), l.x(), l.y()); };
  // The neck (acromia midpoint) is a reference that grounding moved alike.
  const V neck_lab(0, 1.45, 0);
  const ptnet::Pose& p = m.frames[0];
  EXPECT_LT((p[ptnet::kRightHip] - p[ptnet::kNeck] - (world(hip_r_lab) - world(neck_lab))).norm(), 1e-6);  // float tracks
  EXPECT_LT((p[ptnet::kLeftHip] - p[ptnet::kNeck] - (world(hip_l_lab) - world(neck_lab))).norm(), 1e-6);
  EXPECT_LT((p[ptnet::kPelvis] - 0.5 * (p[ptnet::kLeftHip] + p[ptnet::kRightHip])).norm(), 1e-12);
  // Knees and ankles at their markers' midpoints.
  const V knee_r = 0.5 * (s.at[std::size_t(s.index("R.Knee.Lat"))] + s.at[std::size_t(s.index("R.Knee.Med"))]) / 1000;
  EXPECT_LT((p[ptnet::kRightKnee] - p[ptnet::kNeck] - (world(knee_r) - world(neck_lab))).norm(), 1e-6);
  // Right is right: the body faces lab +X, up is lab +Y, so its left is
  // up x forward in the world.
  const V left = V::UnitZ().cross(world(V::UnitX()));
  EXPECT_NEAR((p[ptnet::kLeftHip] - p[ptnet::kRightHip]).dot(left), 2 * (0.33 * pw + 0.0073), 1e-6);
}

TEST(Markers, AStaticTrialRebuildsMissingKneeAndAnkleMarkers) {
  const Standing s = standing();
  const auto frames = moved(s, 40, 50);
  // The trial without the knee and ankle markers; the static trial with them.
  std::vector<std::string> names;
  std::vector<int> keep;
  for (std::size_t m = 0; m < s.names.size(); ++m)
    if (s.names[m].find("Knee") == std::string::npos && s.names[m].find("Ankle") == std::string::npos)
      names.push_back(s.names[m]), keep.push_back(int(m));
  std::vector<std::vector<V>> dyn;
  for (const auto& f : frames) {
    std::vector<V> d;
    for (int m : keep) d.push_back(f[std::size_t(m)]);
    dyn.push_back(d);
  }
  const std::string static_path = write_temp("static.trc", trc_text(s.names, std::vector<std::vector<V>>(10, s.at), 50));
  ptnet::MotionOptions o = keep_rate();
  o.static_markers = static_path;
  ptnet::MarkerReport report;
  const ptnet::Motion rebuilt = ptnet::motion_from_trc(ptnet::parse_trc(trc_text(names, dyn, 50), "d.trc"), o, &report);
  EXPECT_EQ(report.calibrated.size(), 8u);
  // The same trial with every marker: the same knees and ankles.
  const ptnet::Motion full = ptnet::motion_from_trc(ptnet::parse_trc(trc_text(s.names, frames, 50), "f.trc"), keep_rate());
  ASSERT_EQ(rebuilt.size(), full.size());
  for (int t = 0; t < full.size(); t += 13)
    for (int j : {ptnet::kLeftKnee, ptnet::kRightKnee, ptnet::kLeftAnkle, ptnet::kRightAnkle}) {
      const V a = rebuilt.frames[std::size_t(t)][j] - rebuilt.frames[std::size_t(t)][ptnet::kNeck];
      const V b = full.frames[std::size_t(t)][j] - full.frames[std::size_t(t)][ptnet::kNeck];
      EXPECT_LT((a - b).norm(), 1e-6) << ptnet::joint_name(j) << " frame " << t;
    }
  fs::remove(static_path);
}

TEST(Markers, ShortGapsAreFilledSmoothlyAndLongOnesNamed) {
  // One marker on a smooth path at 100 Hz (metres, z up), a gap of 6 samples.
  auto path = [](double t) { return Eigen::Vector3f(float(std::sin(t)), float(0.5 + 0.1 * t * t), float(0.02 * t)); };
  ptnet::detail::Tracks t;
  t.frames = 60;
  t.rate_hz = 100;
  t.names = {"M"};
  t.xyz.emplace_back();
  for (int f = 0; f < 60; ++f) t.xyz[0].push_back(path(f / 100.0));
  for (int f = 20; f < 26; ++f) t.xyz[0][std::size_t(f)] = Eigen::Vector3f::Constant(NAN);
  std::vector<ptnet::detail::Gap> long_gaps;
  EXPECT_EQ(ptnet::detail::fill_gaps(t, 0, 0.1, &long_gaps), 6);
  EXPECT_TRUE(long_gaps.empty());
  for (int f = 20; f < 26; ++f) EXPECT_LT((t.at(f, 0) - path(f / 100.0)).norm(), 0.5e-3) << f;
  // Eleven samples (0.11 s) is beyond 0.1 s: left as a long gap.
  for (int f = 30; f < 41; ++f) t.xyz[0][std::size_t(f)] = Eigen::Vector3f::Constant(NAN);
  EXPECT_EQ(ptnet::detail::fill_gaps(t, 0, 0.1, &long_gaps), 0);
  ASSERT_EQ(long_gaps.size(), 1u);
  EXPECT_EQ(long_gaps[0].begin, 30);
  EXPECT_EQ(long_gaps[0].end, 41);
  // In a trial, a long gap of a marker no segment can rebuild is named.
  const Standing s = standing();
  auto frames = moved(s, 60, 100);
  const int acromion = s.index("R.Acromium");
  for (int f = 30; f < 41; ++f) frames[std::size_t(f)][std::size_t(acromion)] = V(NAN, NAN, NAN);
  try {
    ptnet::motion_from_trc(ptnet::parse_trc(trc_text(s.names, frames, 100), "g.trc"), keep_rate());
    ADD_FAILURE();
  } catch (const ptnet::Error& e) {
    EXPECT_STREQ(e.what(), "g.trc: marker 'R.Acromium' (r_shoulder) is missing in frames 31-41 (0.300-0.400 s); "
                           "gaps up to 0.1 s are filled");
  }
}

TEST(Markers, AFileNoMapPlacesListsItsMarkers) {
  const Standing s = standing();
  std::vector<std::string> names = s.names;
  for (auto& n : names) n = "X" + n;  // no shipped map knows these
  const ptnet::Trc trc = ptnet::parse_trc(trc_text(names, moved(s, 2, 100), 100), "odd.trc");
  try {
    ptnet::motion_from_trc(trc, keep_rate());
    ADD_FAILURE();
  } catch (const ptnet::Error& e) {
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("odd.trc: no shipped marker map (common, delaware, plugin-gait) places the markers", 0), 0u) << w;
    EXPECT_NE(w.find("the file has XR.ASIS XR.Thigh.Upper"), std::string::npos) << w;
    EXPECT_EQ(w.find('\n'), std::string::npos);
  }
  // A user's map for these names places them.
  std::string map = "map = x\n";
  const char* pairs[][2] = {{"r_asis", "XR.ASIS"}, {"l_asis", "XL.ASIS"}, {"sacrum", "XV.Sacral"},
                            {"r_heel", "XR.Heel"}, {"l_heel", "XL.Heel"}, {"r_toe_tip", "XR.Toe.Tip"},
                            {"l_toe_tip", "XL.Toe.Tip"}, {"r_shoulder", "XR.Acromium"}, {"l_shoulder", "XL.Acromium"}};
  for (const auto& p : pairs) map += std::string(p[0]) + " = " + p[1] + "\n";
  ptnet::MotionOptions o = keep_rate();
  o.marker_map = write_temp("x.map", map);
  ptnet::MarkerReport report;
  EXPECT_EQ(ptnet::motion_from_trc(trc, o, &report).size(), 2);
  EXPECT_EQ(report.map, "x");
  fs::remove(o.marker_map);
}

TEST(Belt, ATreadmillGaitIsFoundAndRemovedAndOvergroundIsLeftAlone) {
  // Two feet stepping on a belt at 1.2 m/s under a pelvis that stays: each
  // foot in stance half the cycle (flat, carried back), in swing the other
  // half (lifted, brought forward).
  const double belt = 1.2, fps = 60, period = 1.0;
  ptnet::Motion m;
  m.fps = fps;
  for (int f = 0; f < 240; ++f) {
    const double t = f / fps;
    ptnet::Pose p{};
    p[ptnet::kPelvis] = V(0, 0, 0.9);
    for (int s = 0; s < 2; ++s) {
      const double phase = std::fmod(t / period + 0.5 * s, 1.0);
      const double stance = phase < 0.5;
      const double x = stance ? 0.3 - belt * phase * period : -0.3 + 0.6 * (phase - 0.5) * 2;
      const double lift = stance ? 0 : 0.1 * std::sin(M_PI * (phase - 0.5) * 2);
      const double y = s == 0 ? 0.1 : -0.1;
      const int ankle = s == 0 ? ptnet::kLeftAnkle : ptnet::kRightAnkle;
      p[ankle] = V(x, y, 0.07 + lift);
      p[ankle + 1] = p[ankle] + V(0.14, 0, -0.053);
      p[ankle - 1] = p[ankle] + V(0, 0, 0.43);
      p[ankle - 2] = V(0, y, 0.9);
    }
    m.frames.push_back(p);
  }
  const Eigen::Vector2d v = ptnet::treadmill_belt_velocity(m);
  EXPECT_NEAR(v.x(), -belt, 0.02 * belt);
  EXPECT_NEAR(v.y(), 0, 0.01);
  // Without the belt the same gait is overground: no belt, the body travels.
  const ptnet::Motion over = ptnet::without_belt(m, v);
  EXPECT_EQ(ptnet::treadmill_belt_velocity(over), Eigen::Vector2d::Zero());
  EXPECT_NEAR(over.frames.back()[ptnet::kPelvis].x() - over.frames.front()[ptnet::kPelvis].x(), belt * 239 / fps, 0.05);
}

TEST(RealGait, BothTrialsReadWithTheShippedMapAndTheirStaticTrials) {
  const std::string dir = PTNET_SHARED_GAIT;
  if (!fs::exists(dir + "/walk_s01.trc")) GTEST_SKIP() << "../shared/real-gait not found";
  struct Case {
    const char* trial;
    double stature_m, belt_lo, belt_hi;
    int frames;
  };
  for (const Case& c : {Case{"walk_s01", 1.803, 1.0, 1.3, 151}, Case{"run_s02", 1.83, 3.6, 4.2, 600}}) {
    SCOPED_TRACE(c.trial);
    ptnet::MotionOptions o;
    o.fps = 0;
    o.static_markers = dir + "/" + c.trial + "_static.trc";
    ptnet::MarkerReport report;
    const ptnet::Motion m = ptnet::load_motion(dir + "/" + c.trial + ".trc", o);
    ptnet::motion_from_trc(ptnet::read_trc(dir + "/" + c.trial + ".trc"), o, &report);
    EXPECT_EQ(m.size(), c.frames);
    EXPECT_EQ(m.fps, 60);
    EXPECT_EQ(report.map, "delaware");
    EXPECT_EQ(report.placed.size(), 31u);
    EXPECT_EQ(report.calibrated.size(), 8u);  // knee and ankle markers from the static trial
    EXPECT_NEAR(report.stature_m, c.stature_m, 0.1);
    EXPECT_GT(report.belt_speed_mps, c.belt_lo);
    EXPECT_LT(report.belt_speed_mps, c.belt_hi);
    const double h = ptnet::standing_height(m);
    EXPECT_GT(h, 1.6);
    EXPECT_LT(h, 2.0);
  }
}
