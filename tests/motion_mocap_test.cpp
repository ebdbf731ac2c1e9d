// Every real clip in ../shared/mocap (clips.csv: CMU 31-joint at 120 fps
// with a T-pose frame 0, Character Creator 100/101-joint in cm at 60 fps)
// reads, maps to the canonical joints, has the units clips.csv states,
// stands 1.4-2.1 m tall with its feet on the ground, and resamples to 30 Hz.
// Skips when ../shared/mocap is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "motion/motion_internal.hpp"
#include "ptnet/motion.hpp"

namespace {

struct Clip {
  std::string file, rig;
  double fps = 0, metres_per_unit = 0;
  int frames = 0;
};

const std::string kMocap = PTNET_SHARED_MOCAP;

std::vector<Clip> read_clips() {
  std::ifstream in(kMocap + "/clips.csv");
  std::string line;
  std::getline(in, line);  // file,subject,trial,category,take,rig,fps,frames,metres_per_unit,up
  std::vector<Clip> clips;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    if (f.size() < 10) continue;
    clips.push_back({f[0], f[5], std::stod(f[6]), std::stod(f[8]), std::stoi(f[7])});
  }
  return clips;
}

}  // namespace

TEST(MotionMocap, EveryClipReadsMapsStandsAndResamples) {
  if (!std::filesystem::exists(kMocap + "/clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  const std::vector<Clip> clips = read_clips();
  ASSERT_GE(clips.size(), 11u);
  for (const Clip& c : clips) {
    SCOPED_TRACE(c.file);
    const ptnet::Bvh bvh = ptnet::read_bvh(kMocap + "/" + c.file);
    EXPECT_EQ(bvh.frames(), c.frames);
    EXPECT_NEAR(bvh.fps(), c.fps, 0.01);
    EXPECT_NEAR(ptnet::metres_per_unit(bvh, ptnet::Units::automatic, ptnet::UpAxis::y),
                c.metres_per_unit, 1e-4);
    const auto map = ptnet::map_canonical(bvh);
    const bool cmu = c.rig == "cmu_31";
    EXPECT_EQ(bvh.joints[std::size_t(map[ptnet::kLeftShoulder])].name,
              cmu ? "LeftArm" : "CC_Base_L_Upperarm");
    EXPECT_EQ(bvh.joints[std::size_t(map[ptnet::kRightAnkle])].name,
              cmu ? "RightFoot" : "CC_Base_R_Foot");
    const double scale = c.metres_per_unit;
    EXPECT_EQ(ptnet::is_tpose(bvh, 0, map, scale, ptnet::UpAxis::y), cmu);
    EXPECT_FALSE(ptnet::is_tpose(bvh, 1, map, scale, ptnet::UpAxis::y));

    const ptnet::Motion m = ptnet::motion_from_bvh(bvh, ptnet::MotionOptions{});
    EXPECT_EQ(m.name, c.file.substr(0, c.file.size() - 4));
    EXPECT_DOUBLE_EQ(m.fps, 30.0);
    const int kept = c.frames - (cmu ? 1 : 0);  // T-pose dropped
    EXPECT_EQ(m.size(), int(std::floor((kept - 1) * bvh.frame_time * 30 + 1e-6)) + 1);

    const double height = ptnet::standing_height(m);
    EXPECT_GE(height, 1.4);
    EXPECT_LE(height, 2.1);

    // Feet on the ground: the lowest sole point sits within a few cm of
    // z = 0 in most frames (median within 3 cm; 80 % of frames in
    // [-5, +8] cm, the rest being jumps, squats with feet through the floor,
    // or one-legged poses).
    std::vector<double> low;
    for (const ptnet::Pose& p : m.frames) low.push_back(ptnet::lowest_foot_z(p));
    std::vector<double> sorted = low;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_LT(std::abs(sorted[sorted.size() / 2]), 0.03);
    const auto near =
        std::count_if(low.begin(), low.end(), [](double z) { return z > -0.05 && z < 0.08; });
    EXPECT_GE(double(near) / double(low.size()), 0.8);
    // Body upright: head above the pelvis above the ankles in the first frame.
    const ptnet::Pose& p0 = m.frames[0];
    EXPECT_GT(p0[ptnet::kHead].z(), p0[ptnet::kPelvis].z() + 0.3);
    EXPECT_GT(p0[ptnet::kPelvis].z(), p0[ptnet::kLeftAnkle].z() + 0.6);
  }
}

TEST(MotionMocap, WriterRoundTripOnARealClip) {
  if (!std::filesystem::exists(kMocap + "/clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  for (const char* file : {"002_01.bvh", "141_15.bvh"}) {
    SCOPED_TRACE(file);
    const ptnet::Bvh a = ptnet::read_bvh(kMocap + "/" + file);
    const ptnet::Bvh b = ptnet::parse_bvh(ptnet::format_bvh(a), "copy.bvh");
    const double scale = ptnet::metres_per_unit(a, ptnet::Units::automatic, ptnet::UpAxis::y);
    const auto pa = ptnet::forward_kinematics(a, scale, ptnet::UpAxis::y);
    const auto pb = ptnet::forward_kinematics(b, scale, ptnet::UpAxis::y);
    ASSERT_EQ(pa.size(), pb.size());
    double worst = 0;
    for (std::size_t i = 0; i < pa.size(); ++i) worst = std::max(worst, (pa[i] - pb[i]).norm());
    EXPECT_LT(worst, 1e-4);
  }
}
