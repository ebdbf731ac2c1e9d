// The fast rasteriser and foundation (src/sim: detail::Rasteriser and
// Foundation; spans, affine stepping, SSE2, a histogram for the sink
// level) held to the plain ones of tests/support/reference_rasteriser over
// poses that reach their paths: two
// feet, one foot, a heel raised, a yawed stance, tilt towards the toes and
// sideways (clamped at 0.6 standard deviations), a load beyond what the
// maximum sink carries, a foot off the mat's side, toes off its end, a
// kneeling lunge (knee and hand capsules beside a sole) on and off the mat,
// airborne, wholly off the mat; and frames of a procedural walk and of a
// real CMU walk (skipped when the shared mocap folder is absent), on two
// bodies, at 1 to 5 samples per cell side, one rasteriser reused across
// frames (as simulate() does).
//
// What must agree, and how closely (u = 2^-24, float's unit roundoff; S
// samples per cell side; Z the largest |height| of the frame's samples and
// its level):
//  1. The sink level. The fast path bins the heights within max_sink of the
//     lowest into 64 bins and solves the sum of penetrations linearly within
//     the bin where it reaches the load, assuming the whole bin below the
//     level. The sum is exact at the bin edges, so the exact root (the
//     reference's, on the sorted heights) lies in the same bin:
//       |level - exact| <= max_sink / 64 + e_z.
//  2. Given the fast path's level (from its trace's sink_m), the map, cell
//     by cell. A sample's height differs from the reference's by at most an
//     ulp (the plane's height is rounded to float from doubles that differ
//     in their last bits, stepped along a row against computed directly),
//     the level and the lowest height by an ulp each: a penetration by at
//     most e_z = 6 u Z. The fast path then rounds each penetration to float
//     (u), sums S^2 of them in float ((S^2 - 1) u), multiplies by 1 / S^2 in
//     float (2 u): a cell's mean P is off by at most eta = (S^2 + 3) u
//     relative. The tilt's moments come from those means: in coordinates
//     whitened by the contact's covariance the centroid moves by at most
//     1.5 eta (the penetration-weighted mean distance is <= sqrt 2), the
//     covariance by 3 eta relative, so g (at most 0.6 long there) by 3.5
//     eta, and the weight 1 + g . (r - c) of a cell at Mahalanobis distance
//     m from the centroid by at most 4 eta (1 + m). The weighted mean is
//     rounded to float (u), the load scaling divides by the sum of those
//     (eta) and the product is rounded to float (u). So, with the frame's
//     largest weight w, distance m, mean penetration P and pressure p:
//       |p - p_ref| <= scale w e_z + 3 eta p_max + 4 eta (1 + m) scale P
//     (eta is 7e-7 at S = 3).
//  3. The trace, from the same level: each force within load (3 eta + 4 eta
//     (1 + m) r) + scale ds^2 w e_z x (samples pressed), r the sum of the
//     penetrations over the sum of the weighted ones; cop_u within twice a
//     force's relative bound plus 4 u (u is rounded to float in another
//     order); the area within ds^2 per sample whose penetration is within
//     e_z of 0.
// The test prints the largest error seen as a fraction of its bound.
// The map without a trace (SSE2 lanes, the off-mat shortcut) must be the
// map with one, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/anthropometry.hpp"
#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "sim/sim_internal.hpp"
#include "sim_poses.hpp"
#include "support/reference_rasteriser.hpp"

namespace ptnet {
namespace {

using test::RefSample;

constexpr double kU = 1.0 / (1 << 24);  // float's unit roundoff
constexpr double kG = anthropometry::kGravity;

// One frame: a pose in mat coordinates, its load and where it should act.
struct Frame {
  std::string name;
  const Body* body;
  Pose pose;
  double load_n;
  std::optional<Eigen::Vector2d> target;
};

// The largest errors seen, as fractions of their bounds.
struct Worst {
  double level = 0, map = 0, force = 0, cop = 0;
  int frames = 0, contact = 0;
};

// What the fast path gives for one frame (with its trace, and the map again
// without one).
struct Fast {
  std::vector<float> kpa, kpa_untraced;
  FrameTrace trace;
};

// The simulator's rasteriser and foundation for one option set, reused
// across frames as simulate() reuses them.
struct FastPath {
  explicit FastPath(const SimOptions& o)
      : raster(o.mat, o.subsamples, o.compliance_m + o.max_sink_m),
        foundation(raster.depth().grid, o.compliance_m, o.max_sink_m) {}
  detail::Rasteriser raster;
  detail::Foundation foundation;
};

Fast run_fast(FastPath& r, const Frame& f, const SimOptions& o) {
  const PosedBody posed = pose_body(*f.body, f.pose);
  const double k = o.stiffness_kpa_per_mm * 1e6;
  const Eigen::Vector2d* target = f.target ? &*f.target : nullptr;
  Fast out;
  out.kpa.assign(std::size_t(o.mat.cells()), 0.0f);
  out.kpa_untraced = out.kpa;
  r.raster.rasterise(*f.body, posed, true);
  r.foundation.distribute(r.raster.depth(), f.load_n, k, target, out.kpa.data(), &out.trace);
  r.raster.rasterise(*f.body, posed, false);
  r.foundation.distribute(r.raster.depth(), f.load_n, k, target, out.kpa_untraced.data(), nullptr);
  return out;
}

// The frame's maps and traces compared, within the bounds of the top.
void check_frame(FastPath& r, const Frame& f, const SimOptions& o, Worst& worst) {
  const std::string at =
      f.name + " on " + f.body->spec().id + " at S = " + std::to_string(o.subsamples);
  const Fast fast = run_fast(r, f, o);
  ++worst.frames;
  ASSERT_EQ(0,
            std::memcmp(fast.kpa.data(), fast.kpa_untraced.data(), fast.kpa.size() * sizeof(float)))
      << at << ": the map without a trace differs";
  const std::vector<RefSample> samples =
      test::reference_depth(*f.body, pose_body(*f.body, f.pose), o);
  const double exact = test::reference_sink_level(samples, f.load_n, o);
  const Eigen::Vector2d* target = f.target ? &*f.target : nullptr;
  const bool carried = test::reference_distribute(samples, exact, f.load_n, target, o).scale > 0;
  if (!carried) {
    EXPECT_TRUE(std::all_of(fast.kpa.begin(), fast.kpa.end(), [](float v) { return v == 0; }))
        << at;
    EXPECT_EQ(fast.trace.load_n, 0) << at;
    return;
  }
  ++worst.contact;
  ASSERT_GT(fast.trace.load_n, 0) << at
                                  << ": the reference carries the load, the fast path does not";
  float zlo = samples[0].z;
  for (const RefSample& s : samples) zlo = std::min(zlo, s.z);
  const double level = fast.trace.sink_m + zlo;
  const float lv = float(level);
  double zmax = std::abs(level);
  for (const RefSample& s : samples) zmax = std::max(zmax, double(std::abs(s.z)));
  const double e_z = 6 * kU * zmax;

  // 1. The sink level.
  const double bin = o.max_sink_m / 64;
  EXPECT_LE(std::abs(level - exact), bin + e_z) << at;
  worst.level = std::max(worst.level, std::abs(level - exact) / (bin + e_z));

  // 2. The map at the fast path's level.
  const test::ReferenceFrame ref = test::reference_distribute(samples, lv, f.load_n, target, o);
  ASSERT_GT(ref.scale, 0) << at;
  const double eta = (o.subsamples * o.subsamples + 3) * kU;
  const double dw = 4 * eta * (1 + ref.max_mahalanobis);  // a weight's error
  const double p_max = *std::max_element(ref.kpa.begin(), ref.kpa.end());
  const double tol_map =
      ref.scale * ref.max_weight * e_z + 3 * eta * p_max + dw * ref.scale * ref.max_penetration_m;
  double map_err = 0;
  int worst_cell = 0;
  for (int c = 0; c < o.mat.cells(); ++c) {
    const double e = std::abs(fast.kpa[std::size_t(c)] - ref.kpa[std::size_t(c)]);
    if (e > map_err) map_err = e, worst_cell = c;
  }
  EXPECT_LE(map_err, tol_map) << at << ": cell " << worst_cell << " reads "
                              << fast.kpa[std::size_t(worst_cell)] << " kPa, the reference "
                              << ref.kpa[std::size_t(worst_cell)];
  worst.map = std::max(worst.map, map_err / tol_map);

  // 3. The trace.
  int pressed = 0, near_level = 0;
  for (const RefSample& s : samples) pressed += s.z < lv, near_level += std::abs(lv - s.z) <= e_z;
  const double ds2 = std::pow(o.mat.pitch_m / o.subsamples, 2);
  const double tol_force = f.load_n * (3 * eta + dw * ref.unweighted_ratio) +
                           ref.scale * 1000 * ds2 * ref.max_weight * e_z * pressed;
  const FrameTrace &a = fast.trace, &b = ref.trace;
  EXPECT_EQ(a.load_n, b.load_n) << at;
  auto force = [&](double x, double y, const char* what) {
    EXPECT_NEAR(x, y, tol_force) << at << ": " << what;
    worst.force = std::max(worst.force, std::abs(x - y) / tol_force);
  };
  force(a.other_n, b.other_n, "other_n");
  for (int k = 0; k < 2; ++k) {
    const FootLoad &x = a.foot[std::size_t(k)], &y = b.foot[std::size_t(k)];
    force(x.force_n, y.force_n, "force_n");
    force(x.heel_n, y.heel_n, "heel_n");
    force(x.forefoot_n, y.forefoot_n, "forefoot_n");
    EXPECT_NEAR(x.area_m2, y.area_m2, ds2 * (near_level + 1e-6)) << at << ": area_m2";
    if (y.force_n > tol_force) {
      const double tol_cop = 2 * tol_force / y.force_n + 4 * kU;
      EXPECT_NEAR(x.cop_u, y.cop_u, tol_cop) << at << ": cop_u";
      worst.cop = std::max(worst.cop, std::abs(x.cop_u - y.cop_u) / tol_cop);
    }
  }
}

// Frames posed by hand (mat coordinates) on `body`.
std::vector<Frame> posed_frames(const Body& body) {
  using test::rest_pose;
  const double H = body.spec().height_cm, W = body.mass_kg() * kG;
  std::vector<Frame> f;
  f.push_back({"two feet", &body, rest_pose(H), W, Eigen::Vector2d(0.01, 0.0)});
  f.push_back({"two feet, no tilt", &body, rest_pose(H, 0.1, -0.05), W, std::nullopt});
  Pose one = rest_pose(H);
  test::move_leg(one, /*left=*/false, Eigen::Vector3d(0, 0, 0.10));
  f.push_back({"one foot", &body, one, 1.3 * W, Eigen::Vector2d(0.0, 0.1)});
  Pose heel = rest_pose(H);
  heel[kLeftAnkle].z() += 0.03;  // the left heel raised: its hindfoot tilts onto the ball
  f.push_back({"heel raised", &body, heel, W, Eigen::Vector2d(0.05, 0.02)});
  Pose yawed = rest_pose(H, 0.2, 0.05);
  test::rotate_pose(yawed, 0.5, 0.2, 0.05);
  f.push_back({"yawed", &body, yawed, W, Eigen::Vector2d(0.25, 0.05)});
  f.push_back({"tilt to the toes", &body, rest_pose(H), W, Eigen::Vector2d(0.5, 0.0)});
  f.push_back({"tilt sideways", &body, rest_pose(H), W, Eigen::Vector2d(0.0, -0.4)});
  f.push_back({"beyond the max sink", &body, rest_pose(H), 8 * W, Eigen::Vector2d(0.02, 0.0)});
  f.push_back({"foot off the side", &body, rest_pose(H, 0, 0.22), W, Eigen::Vector2d(0.0, 0.22)});
  f.push_back({"toes off the end", &body, rest_pose(H, 0.7, 0), W, Eigen::Vector2d(0.75, 0.0)});
  f.push_back({"kneel", &body, test::kneel_pose(body, 0.2, 0), W, Eigen::Vector2d(0.15, 0.02)});
  f.push_back({"kneel, shank off the end", &body, test::kneel_pose(body, -0.45, 0), W,
               Eigen::Vector2d(-0.5, 0.0)});
  Pose up = rest_pose(H);
  for (auto& j : up) j.z() += 0.03;
  f.push_back({"airborne", &body, up, W, std::nullopt});
  f.push_back({"wholly off the mat", &body, rest_pose(H, 0, 1.0), W, Eigen::Vector2d(0.0, 1.0)});
  f.push_back({"no load", &body, rest_pose(H), 0.0, std::nullopt});
  return f;
}

// Every `step`-th frame of a source motion on `body`, as simulate() poses
// it on the mat (placement, foot pitch, floor) with its load and
// zero-moment point.
std::vector<Frame> motion_frames(const std::string& name, const Motion& source, const Body& body,
                                 int step) {
  const SimOptions o;
  const double h = body.spec().height_cm;
  const MotionPlacement place = place_copy(source, h, o);
  const Motion m = detail::pitch_corrected(retarget(source, h), place.foot_pitch);
  const detail::ComTrack com = detail::com_track(m, body, o.com_filter_hz);
  std::vector<Frame> out;
  for (int t = 0; t < m.size(); t += step) {
    const Eigen::Vector2d c = place.centre[std::size_t(t)];
    const double floor = place.floor.empty() ? 0.0 : place.floor[std::size_t(t)];
    Pose local;
    for (int j = 0; j < kJointCount; ++j) {
      const Eigen::Vector2d d = m.frames[std::size_t(t)][j].head<2>() - c;
      local[j] = Eigen::Vector3d(place.axis.dot(d), place.left.dot(d),
                                 m.frames[std::size_t(t)][j].z() - floor);
    }
    const Eigen::Vector2d d = com.zmp[std::size_t(t)] - c;
    out.push_back({name + " frame " + std::to_string(t), &body, local, com.load_n[std::size_t(t)],
                   Eigen::Vector2d(place.axis.dot(d), place.left.dot(d))});
  }
  return out;
}

const std::vector<BodySpec> kBodies = {
    {"f150", Sex::female, 150, 48, "retargeted"},
    {"m196", Sex::male, 196, 104, "retargeted"},
};

TEST(SimReference, FastPathMatchesThePlainOne) {
  std::vector<Body> bodies(kBodies.begin(), kBodies.end());
  GenerateOptions g;
  g.performer = 2;
  g.seconds = 4;
  const Motion walk = generate_motion(g);
  const std::string mocap = PTNET_SHARED_MOCAP;
  std::optional<Motion> real;
  if (std::filesystem::exists(mocap + "/clips.csv")) {
    const std::vector<ClipSource> clips =
        clips_from_files({mocap + "/002_01.bvh"}, mocap + "/clips.csv", {});
    real = load_clip(clips.at(0), 30);
  } else {
    std::printf("%s not found (the shared CMU clips): the real walk's frames are skipped\n",
                mocap.c_str());
  }
  std::vector<Frame> frames;
  for (const Body& body : bodies) {
    for (Frame& f : posed_frames(body)) frames.push_back(f);
    for (Frame& f : motion_frames("procedural walk", walk, body, 4)) frames.push_back(f);
    if (real)
      for (Frame& f : motion_frames("002_01", *real, body, 4)) frames.push_back(f);
  }
  Worst worst;
  for (int s = 1; s <= 5; ++s) {
    SimOptions o;
    o.subsamples = s;
    FastPath r(o);
    for (const Frame& f : frames) check_frame(r, f, o, worst);
  }
  std::printf(
      "%d frames (%d carrying load); largest error / bound: level %.3g, map %.3g, force %.3g, "
      "cop_u %.3g\n",
      worst.frames, worst.contact, worst.level, worst.map, worst.force, worst.cop);
}

// Off the mat a position keeps its lowest surface, as on the mat (before,
// every surface's record there was a sample of its own: a position under a
// capsule's overlapping spheres counted up to ~3 times, and kneeling with
// the shank over the mat's end the 104 kg body's left sole carried 250 N
// instead of 297 N).
TEST(SimReference, OffTheMatEachPositionCountsOnce) {
  const Body body(kBodies[1]);
  const SimOptions o;
  const double W = body.mass_kg() * kG;
  const PosedBody posed = pose_body(body, test::kneel_pose(body, -0.6, 0));
  const std::vector<RefSample> s = test::reference_depth(body, posed, o);
  const double reference = test::reference_distribute(s, test::reference_sink_level(s, W, o), W, nullptr, o)
                               .trace.foot[0]
                               .force_n;
  FastPath r(o);
  const Fast fast = run_fast(r, {"kneel off the end", &body, test::kneel_pose(body, -0.6, 0), W, std::nullopt}, o);
  EXPECT_GT(reference, 290);
  // Within the fast path's own error (its histogram sink level; FastPathMatchesThePlainOne
  // holds it to its bounds), far from the 47 N the duplicates cost.
  EXPECT_NEAR(fast.trace.foot[0].force_n, reference, 1.0);
}

}  // namespace
}  // namespace ptnet
