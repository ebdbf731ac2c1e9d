// Motions that cannot carry their own dynamics are named (check_dynamics):
// a pelvis whose height the rig never moves while the feet step; stretches
// off the floor that are no flight (standing on a box). A real flight (a
// jump) and a walk are not named. Then the corpus clips of the issue that
// asked for it (skipped without ../shared/mocap-corpus).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/strings.hpp"
#include "sim_poses.hpp"

namespace ptnet {
namespace {

using test::rest_pose;

constexpr double kFps = 30;

// The rest pose of 175 cm, every joint raised by lift(t) (m), for `seconds`.
template <class Lift>
Motion lifted(double seconds, const Lift& lift) {
  Motion m;
  m.fps = kFps;
  for (int t = 0; t < int(seconds * kFps); ++t) {
    Pose p = rest_pose(175);
    for (auto& j : p) j.z() += lift(t / kFps);
    m.frames.push_back(p);
  }
  return m;
}

TEST(SimDynamics, StandingAndAJumpCarryTheirDynamics) {
  const SimOptions o;
  const MotionDynamics standing = check_dynamics(lifted(3, [](double) { return 0.0; }), o);
  EXPECT_EQ(standing.frozen_pelvis, 0);  // the feet never step
  EXPECT_EQ(standing.unsupported, 0);
  // A 0.4 s flight at 1.5 s (apex 0.2 m): the centre of mass falls through it.
  const MotionDynamics jump = check_dynamics(lifted(3, [](double t) {
                                               const double s = t - 1.5;
                                               return s > 0 && s < 0.4 ? 1.962 * s - 4.905 * s * s : 0.0;
                                             }),
                                             o);
  EXPECT_EQ(jump.unsupported, 0);
  EXPECT_TRUE(dynamics_warnings("jump", jump).empty());
}

TEST(SimDynamics, ASeatCarriesWhatTheFeetDoNotAndTheMatSeesOnlyTheFeet) {
  // 1 s standing, 2 s seated (the hips 0.43 m back and down: thighs level,
  // shanks upright, the centre of mass far behind the heels, held still),
  // 1 s standing. A body that sits does not fall: something carries it.
  const double thigh = 0.245 * 1.75;
  Motion m = lifted(4, [](double) { return 0.0; });
  for (int t = 0; t < m.size(); ++t) {
    if (t < kFps || t >= 3 * kFps) continue;
    for (int j = 0; j < kJointCount; ++j) {
      const bool leg = j == kLeftKnee || j == kLeftAnkle || j == kLeftToe || j == kRightKnee || j == kRightAnkle ||
                       j == kRightToe;
      if (!leg) m.frames[std::size_t(t)][j] += Eigen::Vector3d(-thigh, 0, -thigh);
    }
  }
  const SimOptions o;
  const MotionDynamics d = check_dynamics(m, o);
  EXPECT_NEAR(d.carried, 0.5, 0.1);  // the seated half
  EXPECT_EQ(d.unsupported, 0);
  const std::vector<std::string> w = dynamics_warnings("chair", d);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("a seat carries part of the body"), std::string::npos) << w[0];
  EXPECT_EQ(check_dynamics(lifted(4, [](double) { return 0.0; }), o).carried, 0);  // standing: nothing carried
  // The simulation: force balance per frame (the feet's load and the
  // seat's share make the body's weight while it sits still); the seat's
  // share is most of the body, the feet keep some.
  const Body body(BodySpec{"m", Sex::male, 175, 70});
  std::vector<FrameTrace> trace;
  simulate(m, body, o, &trace);
  const double bw = body.mass_kg() * 9.81;
  const FrameTrace& seated = trace[std::size_t(2 * kFps)];
  EXPECT_NEAR(seated.load_n + seated.carried_n, bw, 0.02 * bw);
  EXPECT_GT(seated.carried_n, 0.5 * bw);
  EXPECT_GT(seated.foot[0].force_n + seated.foot[1].force_n, 0.05 * bw);
  const FrameTrace& standing = trace[std::size_t(kFps / 2)];
  EXPECT_EQ(standing.carried_n, 0);
  EXPECT_NEAR(standing.load_n, bw, 0.02 * bw);
}

TEST(SimDynamics, AStepOntoABoxIsNamed) {
  // 1 s on the floor, then 2 s 30 cm up (standing on something), back down.
  const Motion m = lifted(4, [](double t) { return t > 1 && t < 3 ? 0.3 : 0.0; });
  const MotionDynamics box = check_dynamics(m, SimOptions{});
  EXPECT_NEAR(box.unsupported, 0.5, 0.05);
  const std::vector<std::string> w = dynamics_warnings("box", box);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].rfind("box: ", 0), 0u) << w[0];
  EXPECT_NE(w[0].find(" % of frames have no body surface on the floor while the body is carried"), std::string::npos)
      << w[0];
  // The placement simulate already made gives the same check.
  const MotionPlacement place = place_motion(m, SimOptions{});
  const MotionDynamics again = check_dynamics(m, SimOptions{}, &place);
  EXPECT_EQ(again.unsupported, box.unsupported);
  EXPECT_EQ(again.frozen_pelvis, box.frozen_pelvis);
}

TEST(SimDynamics, AFrozenPelvisUnderSteppingFeetIsNamed) {
  // The feet step forward and back (ankles at 0.5 m/s) under a pelvis whose
  // height never changes.
  Motion m;
  m.fps = kFps;
  for (int t = 0; t < 60; ++t) {
    Pose p = rest_pose(175);
    const double swing = 0.1 * std::sin(2 * M_PI * t / kFps);
    for (int j : {kLeftKnee, kLeftAnkle, kLeftToe}) p[j].x() += swing;
    for (int j : {kRightKnee, kRightAnkle, kRightToe}) p[j].x() -= swing;
    m.frames.push_back(p);
  }
  const MotionDynamics d = check_dynamics(m, SimOptions{});
  EXPECT_EQ(d.frozen_pelvis, 1.0);
  const std::vector<std::string> w = dynamics_warnings("rig", d);
  ASSERT_FALSE(w.empty());
  EXPECT_NE(w[0].find("rig: the pelvis height is fixed while the feet step in 100 % of frames"), std::string::npos);
  // A pelvis that moves by a capture's noise is not frozen.
  for (int t = 0; t < m.size(); ++t) m.frames[std::size_t(t)][kPelvis].z() += 1e-4 * std::sin(t);
  EXPECT_EQ(check_dynamics(m, SimOptions{}).frozen_pelvis, 0);
}

TEST(SimDynamics, TheCorpusClipsOfTheIssueAreNamed) {
  const std::string dir = PTNET_SHARED_CORPUS;
  if (!std::filesystem::exists(dir + "/002_03.bvh")) GTEST_SKIP() << "../shared/mocap-corpus not found";
  const SimOptions o;
  for (const char* clip : {"002_01", "002_02", "002_03"})
    EXPECT_EQ(check_dynamics(load_motion(dir + "/" + clip + ".bvh", {}), o).frozen_pelvis, 1.0) << clip;
  for (const char* clip : {"003_01", "003_02"})
    EXPECT_GT(check_dynamics(load_motion(dir + "/" + clip + ".bvh", {}), o).unsupported, 0.3) << clip;
  for (const char* clip : {"005_01", "006_01", "14_06"}) {  // a walk, a walk, squats and jogging
    const MotionDynamics d = check_dynamics(load_motion(dir + "/" + clip + ".bvh", {}), o);
    EXPECT_TRUE(dynamics_warnings(clip, d).empty()) << join(dynamics_warnings(clip, d), "; ");
  }
  // No dancer sits: a cartwheel's hands on the floor support the body, and
  // an arabesque or a pirouette whose load point strays off the feet with
  // the hips high is no seat (15-25 % of these clips' frames, up to 1.4 BW
  // taken off the mat, before the hips' height was part of the rule).
  for (const char* clip : {"005_06", "005_13", "005_19", "141_15"})
    EXPECT_EQ(check_dynamics(load_motion(dir + "/" + clip + ".bvh", {}), o).carried, 0) << clip;
}

}  // namespace
}  // namespace ptnet
