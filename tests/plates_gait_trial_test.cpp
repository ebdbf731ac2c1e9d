// The gait-lab path in a bare clone: the committed synthetic treadmill walk
// of tests/data/gait (scripts/make-gait-trial.py; docs/physics.md, "The
// committed trial"), a marker file and its force plates made as one
// physically consistent trial. Each expected figure below is one the script
// computes from its own skeleton and forces and prints; each tolerance says
// where it comes from (the files' rounding, a documented method), none is
// fitted to a run.
//
//  - The marker path (motion_from_trc): the map, the up axis, the static
//    trial's calibration, the belt, the stature estimate, and the joints:
//    every bone of the canonical 1.75 m skeleton the trial was built on.
//  - The bench (run_gait_trial): what the trial's physics implies for any
//    simulator that takes its load from the centre of mass's acceleration
//    low-passed at 4 Hz and puts a foot in contact where its sole is, and
//    the naive reference's figures, which follow from the plates alone.
//  - The bench's output files (results.json, walk_sim.mot, walk_frames.csv)
//    as digests, in tests/data/gait/bench_digests.txt. Re-blessing, only
//    when the simulator's physics changes on purpose (state which figures
//    moved and why in the commit body), is one step:
//      PTNET_GOLDEN_BLESS=1 build/tests/plates_gait_trial_test
//    rewrites that file; PTNET_GOLDEN_PRINT=1 prints the lines instead.
//    Each number of a file is digested rounded to float (as the simulator's
//    golden test digests its trace): the figures are doubles through exp,
//    sin and atan2, whose last bits differ between libm's FMA and non-FMA
//    paths (scripts/check-numerics.sh), a float's do not.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "core/hash.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/plates.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kDir = std::string(PTNET_TEST_DATA) + "/gait";
constexpr double kH = 1.75;         // the subject's stature (m)
constexpr double kBelt = 1.10;      // m/s
constexpr double kFrame = 1.0 / 60;  // s

double dist(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm(); }

ptnet::Motion load(ptnet::MarkerReport* report) {
  ptnet::MotionOptions o;
  o.fps = 60;  // the file's rate: no resampling
  o.static_markers = kDir + "/walk_static.trc";
  return ptnet::motion_from_trc(ptnet::read_trc(kDir + "/walk.trc"), o, report);
}

TEST(GaitTrial, TheMarkerPathRecoversTheSkeletonItWasMadeOn) {
  ptnet::MarkerReport r;
  const ptnet::Motion m = load(&r);
  ASSERT_EQ(m.size(), 151);
  // load_motion reads a .trc as markers, as motion_from_trc does.
  ptnet::MotionOptions o;
  o.fps = 60;
  o.static_markers = kDir + "/walk_static.trc";
  const ptnet::Motion loaded = ptnet::load_motion(kDir + "/walk.trc", o);
  ASSERT_EQ(loaded.size(), m.size());
  for (int t = 0; t < m.size(); ++t)
    for (int j = 0; j < ptnet::kJointCount; ++j)
      ASSERT_EQ(loaded.frames[std::size_t(t)][j], m.frames[std::size_t(t)][j]) << t << " " << j;
  EXPECT_EQ(r.map, "delaware");
  EXPECT_EQ(r.up_axis, ptnet::UpAxis::y);
  EXPECT_EQ(r.calibrated.size(), 8u);  // knee and ankle markers, from the static trial's clusters
  EXPECT_EQ(r.gap_filled_frames, 0);
  // The documented estimate (the hip-heel distance of the straightest legs,
  // 95th percentile, plus the heel marker's height, over the canonical hip
  // height) on the skeleton of 1.75 m the trial was made on: 1.758 m, within
  // 1 % (the walk's legs are never quite straight; the former estimate from
  // the median hip height gave 1.720, 1.7 % short).
  EXPECT_NEAR(r.stature_m, 1.75, 0.0175);
  // The belt: the lowest sole point of the planted foot moves at 1.10 m/s
  // while the foot is flat and turns with it in the heel and forefoot
  // rockers, which the median takes in: not slower, and within 5 %.
  EXPECT_GE(r.belt_speed_mps, kBelt - 0.005);
  EXPECT_LE(r.belt_speed_mps, kBelt * 1.05);
  // Every bone as the canonical skeleton of 1.75 m has it (thigh 0.245 H,
  // shank 0.246 H, ankle -> toe joint 0.0845 H), in every frame: the hips by
  // Harrington, the knees and ankles rebuilt on the clusters, the toe joints
  // 10 mm under the metatarsal markers. 0.5 mm: the markers' rounding
  // (0.005 mm) through the cluster fit, far below.
  for (int t = 0; t < m.size(); ++t) {
    const ptnet::Pose& p = m.frames[std::size_t(t)];
    for (int hip : {ptnet::kLeftHip, ptnet::kRightHip}) {
      ASSERT_NEAR(dist(p[hip], p[hip + 1]), 0.245 * kH, 5e-4) << t;
      ASSERT_NEAR(dist(p[hip + 1], p[hip + 2]), 0.246 * kH, 5e-4) << t;
      ASSERT_NEAR(dist(p[hip + 2], p[hip + 3]), std::hypot(0.0790, 0.030) * kH, 5e-4) << t;
      ASSERT_NEAR(dist(p[ptnet::kPelvis], p[hip]), 0.0475 * kH, 5e-4) << t;
    }
  }
  // Lab X forward, Z right -> world y forward, x right: the left hip on -x.
  EXPECT_LT(m.frames[0][ptnet::kLeftHip].x(), m.frames[0][ptnet::kRightHip].x());
  // The belt removed, every joint moves on by the removed speed x t: the
  // pelvis travels that much further than it does in the lab (where the
  // ASIS, rigid on the pelvis, show its own fore-aft swing).
  const ptnet::Trc trc = ptnet::read_trc(kDir + "/walk.trc");
  auto asis_x = [&](int f) { return 0.0005 * (trc.at(f, trc.find("R.ASIS")).x() + trc.at(f, trc.find("L.ASIS")).x()); };
  const double travel = m.frames.back()[ptnet::kPelvis].y() - m.frames.front()[ptnet::kPelvis].y();
  EXPECT_NEAR(travel, r.belt_speed_mps * 2.5 + asis_x(150) - asis_x(0), 1e-4);
}

const ptnet::GaitTrialResult& bench() {
  static const ptnet::GaitTrialResult r =
      ptnet::run_gait_trial(ptnet::read_gait_trials(kDir + "/trials.csv", "")[0], {});
  return r;
}

TEST(GaitTrial, TheBenchMeetsWhatThePhysicsImplies) {
  const ptnet::GaitTrialResult& r = bench();
  const ptnet::ForceSource &p = r.plates, &s = r.simulated, &n = r.naive;
  ASSERT_EQ(r.time_s.size(), 151u);
  EXPECT_EQ(r.coverage, ptnet::PlateCoverage::all);  // a treadmill: the plates see every step
  EXPECT_EQ(r.flight_frames, 0);
  int whole = 0;
  for (const auto& c : p.contacts) whole += c.whole;
  EXPECT_EQ(whole, 4);  // the trial's 2.5 s hold two whole stances of each foot
  EXPECT_EQ(s.matched, whole);
  // The naive reference is 1 BW while any foot is loaded (every frame of a
  // walk): its RMSE is the plates' own, the script's 0.1659 BW (the files'
  // 0.01 N rounding: < 1e-4).
  EXPECT_NEAR(n.rmse_bw, 0.1659, 5e-4);
  // The simulator's load is m (g + a_z) with the CoM's acceleration
  // low-passed at 4 Hz: on this force that filter alone leaves 0.0267 BW
  // (the script, from the trial's exact CoM); the body's segment model
  // (segment centres at their midpoints, against de Leva's fractions in the
  // trial) adds at most 0.01 and the 4 Hz filter's edge frames 0.01.
  EXPECT_LE(s.rmse_bw, 0.0267 + 0.02);
  EXPECT_LT(s.rmse_bw, n.rmse_bw / 3);
  // Newton over a stride: the impulse is m g T whatever the load model, if
  // the CoM returns to its height; the plates' stride mean is m g exactly.
  EXPECT_LE(s.stride_impulse_error_pct, 1.0);
  // The bar of real walking (docs/physics.md, walk_s01): per-contact peaks
  // within 10 %.
  EXPECT_LE(s.peak_error_pct, 10);
  EXPECT_LT(s.peak_error_pct, n.peak_error_pct);
  // The trial's CoP is prescribed (the script's knots), not the zero-moment
  // point of its own segments, which the simulator follows: the two differ
  // by up to a quarter of the foot (measured 0.200 foot lengths; the naive
  // mid-foot constant 0.166). What holds is that the simulated CoP stays on
  // the stance foot and rolls along it.
  EXPECT_LE(s.cop_rms, 0.25);
  // A foot is in contact while its sole is on the floor: every simulated
  // contact covers the plates' (to a frame), the heel being at the floor at
  // heel strike and the forefoot until toe off.
  for (const auto& c : p.contacts) {
    if (!c.whole) continue;
    bool covered = false;
    for (const auto& x : s.contacts)
      covered |= x.foot == c.foot && x.start_s <= c.start_s + kFrame && x.end_s >= c.end_s - kFrame;
    EXPECT_TRUE(covered) << "contact of foot " << c.foot << " at " << c.start_s << " s";
  }
  EXPECT_NEAR(r.belt_mps, kBelt, kBelt * 0.05);
}

// ------------------------------------------------------------ the digests

// The file's text with every number rounded to float and printed "%.9g"
// (see the top), digested.
std::string float_digest(const std::string& text) {
  ptnet::Fnv1a h;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    const bool starts = std::isdigit(static_cast<unsigned char>(c)) ||
                        ((c == '-' || c == '.') && i + 1 < text.size() &&
                         std::isdigit(static_cast<unsigned char>(text[i + 1])));
    const bool in_word = i > 0 && (std::isalnum(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '_');
    if (starts && !in_word) {
      char* end = nullptr;
      const double v = std::strtod(text.c_str() + i, &end);
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.9g", double(float(v)));
      h.add(buf);
      i = std::size_t(end - text.c_str());
    } else {
      h.add_byte(static_cast<unsigned char>(c));
      ++i;
    }
  }
  return h.hex();
}

const char* const kDigestFile = PTNET_TEST_DATA "/gait/bench_digests.txt";

std::map<std::string, std::string> read_digests() {
  std::map<std::string, std::string> out;
  std::ifstream in(kDigestFile);
  for (std::string line; std::getline(in, line);) {
    std::istringstream w(line);
    std::string name, digest;
    if (line.rfind('#', 0) != 0 && w >> name >> digest) out[name] = digest;
  }
  return out;
}

bool env(const char* name) {
  const char* v = std::getenv(name);
  return v && *v && std::string(v) != "0";
}

TEST(GaitTrial, TheBenchsOutputFilesArePinned) {
  const fs::path dir = fs::temp_directory_path() / ("ptnet_gait_trial_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  ptnet::write_physics_report({bench()}, dir.string(), false);
  const std::map<std::string, std::string> golden = read_digests();
  std::string lines;
  for (const char* f : {"results.json", "walk_sim.mot", "walk_frames.csv"}) {
    const std::string digest = float_digest(ptnet::read_text_file((dir / f).string()));
    lines += std::string(f) + " " + digest + "\n";
    if (env("PTNET_GOLDEN_BLESS") || env("PTNET_GOLDEN_PRINT")) continue;
    const auto it = golden.find(f);
    ASSERT_NE(it, golden.end()) << kDigestFile << " has no digest of " << f << "; bless (see the top)";
    EXPECT_EQ(digest, it->second) << f << " changed; if on purpose (the physics), bless (see the top)";
  }
  fs::remove_all(dir);
  if (env("PTNET_GOLDEN_BLESS")) {
    std::ofstream(kDigestFile) << "# tests/plates_gait_trial_test.cpp: PTNET_GOLDEN_BLESS=1 rewrites this file\n"
                               << lines;
    std::printf("wrote %s:\n%s", kDigestFile, lines.c_str());
  } else if (env("PTNET_GOLDEN_PRINT")) {
    std::printf("%s", lines.c_str());
  }
}

}  // namespace
