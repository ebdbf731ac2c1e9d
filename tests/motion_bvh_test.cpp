// BVH reading and writing, forward kinematics, units, canonical joints,
// resampling, T-pose detection and the foot/height measurements, on small
// hand-written rigs with known answers.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"

namespace fs = std::filesystem;
using namespace ptnet;

namespace {

const std::string kSmall = std::string(PTNET_TEST_DATA) + "/bvh/tpose_cmu_small.bvh";

// Root with 6 channels, one 3-channel child (XYZ order), a 0-channel joint
// and End Sites. 13 channels... no: 6 + 3 + 0 = 9 channels.
const char* kTwoJoint =
    "HIERARCHY\n"
    "ROOT Root\n"
    "{\n"
    "  OFFSET 0 0 0\n"
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation\n"
    "  JOINT Arm\n"
    "  {\n"
    "    OFFSET 1 0 0\n"
    "    CHANNELS 3 Xrotation Yrotation Zrotation\n"
    "    JOINT Tip\n"
    "    {\n"
    "      OFFSET 0 0 2\n"
    "      CHANNELS 0\n"
    "      End Site\n"
    "      {\n"
    "        OFFSET 0 0 1\n"
    "      }\n"
    "    }\n"
    "  }\n"
    "}\n"
    "MOTION\n"
    "Frames: 2\n"
    "Frame Time: 0.04\n"
    "1 2 3 90 0 0 90 0 0\n"
    "0 0 0 0 0 0 0 0 0\n";

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t p = 0; (p = s.find(from, p)) != std::string::npos; p += to.size())
    s.replace(p, from.size(), to);
  return s;
}

void expect_near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol = 1e-12) {
  EXPECT_NEAR((a - b).norm(), 0.0, tol) << "got " << a.transpose() << " want " << b.transpose();
}

// Multiplies every length of a BVH (offsets, position channels) by k.
Bvh scaled(Bvh b, double k) {
  for (BvhJoint& j : b.joints) {
    j.offset *= k;
    j.end_site *= k;
    for (std::size_t c = 0; c < j.channels.size(); ++c)
      if (int(j.channels[c]) < 3)
        for (int f = 0; f < b.frames(); ++f)
          b.values[std::size_t(f) * b.channel_count + j.first_channel + c] *= k;
  }
  return b;
}

Eigen::Quaterniond rotation_of(const Bvh& b, int joint, int frame) {
  const BvhJoint& j = b.joints[std::size_t(joint)];
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (std::size_t c = 0; c < j.channels.size(); ++c) {
    const int ch = int(j.channels[c]);
    if (ch < 3) continue;
    q = q * Eigen::AngleAxisd(b.frame(frame)[j.first_channel + int(c)] * M_PI / 180,
                              Eigen::Vector3d::Unit(ch - 3));
  }
  return q;
}

}  // namespace

TEST(BvhParse, ReadsHierarchyChannelsAndValues) {
  const Bvh b = parse_bvh(kTwoJoint, "two.bvh");
  ASSERT_EQ(b.joints.size(), 3u);
  EXPECT_EQ(b.joints[0].name, "Root");
  EXPECT_EQ(b.joints[1].parent, 0);
  EXPECT_EQ(b.joints[2].parent, 1);
  EXPECT_EQ(b.channel_count, 9);
  EXPECT_EQ(b.joints[1].first_channel, 6);
  EXPECT_EQ(b.joints[2].first_channel, 9);
  EXPECT_TRUE(b.joints[2].channels.empty());
  ASSERT_EQ(b.joints[0].channels.size(), 6u);
  EXPECT_EQ(b.joints[0].channels[3], Channel::Zrotation);
  EXPECT_EQ(b.joints[1].channels[0], Channel::Xrotation);
  EXPECT_TRUE(b.joints[2].has_end_site);
  expect_near(b.joints[2].end_site, {0, 0, 1});
  EXPECT_FALSE(b.joints[0].has_end_site);
  EXPECT_EQ(b.frames(), 2);
  EXPECT_DOUBLE_EQ(b.frame_time, 0.04);
  EXPECT_DOUBLE_EQ(b.fps(), 25.0);
  EXPECT_DOUBLE_EQ(b.frame(0)[6], 90.0);
  EXPECT_EQ(b.find("Arm"), 1);
  EXPECT_EQ(b.find("Nope"), -1);
  EXPECT_EQ(b.source, "two.bvh");
}

TEST(BvhParse, CrlfTabsBomAndBlankLinesGiveTheSameData) {
  const Bvh lf = parse_bvh(kTwoJoint, "a.bvh");
  std::string crlf = replace_all(kTwoJoint, "\n", "\r\n");
  std::string tabs = "\xEF\xBB\xBF" + replace_all(replace_all(kTwoJoint, "  ", "\t"), " ", "\t ");
  tabs += "\n\n";  // trailing blank lines
  for (const std::string& text : {crlf, tabs}) {
    const Bvh b = parse_bvh(text, "b.bvh");
    ASSERT_EQ(b.joints.size(), lf.joints.size());
    for (std::size_t j = 0; j < b.joints.size(); ++j) {
      EXPECT_EQ(b.joints[j].name, lf.joints[j].name);
      EXPECT_EQ(b.joints[j].channels, lf.joints[j].channels);
      expect_near(b.joints[j].offset, lf.joints[j].offset, 0);
    }
    EXPECT_EQ(b.values, lf.values);
  }
  // Line numbers in errors count CRLF lines like LF lines.
  try {
    parse_bvh(replace_all(crlf, "0.04", "0"), "c.bvh");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "c.bvh:23: expected a positive Frame Time (s), found 0");
  }
}

TEST(BvhParse, AcceptsBraceOnNameLineSignsAndExponents) {
  std::string text = replace_all(kTwoJoint, "ROOT Root\n{", "ROOT Root {");
  text = replace_all(text, "1 2 3 90 0 0 90 0 0", "+1 2e0 .3e1 90 -0 0 9E1 0 0");
  const Bvh b = parse_bvh(text, "x.bvh");
  EXPECT_EQ(b.joints[0].name, "Root");
  const double want[] = {1, 2, 3, 90, 0, 0, 90, 0, 0};
  for (int c = 0; c < 9; ++c) EXPECT_DOUBLE_EQ(b.frame(0)[c], want[c]);
}

TEST(Fk, TwoJointRigKnownAnswers) {
  const Bvh b = parse_bvh(kTwoJoint, "two.bvh");
  // z up: no axis change. Frame 0: root at (1,2,3) turned 90 deg about z;
  // Arm turned 90 deg about x. Arm = (1,2,3) + Rz90 (1,0,0) = (1,3,3);
  // Tip = Arm + Rz90 Rx90 (0,0,2) = (1,3,3) + Rz90 (0,-2,0) = (3,3,3).
  std::vector<Eigen::Vector3d> p;
  forward_kinematics_frame(b, 0, 1.0, UpAxis::z, p);
  ASSERT_EQ(p.size(), 3u);
  expect_near(p[0], {1, 2, 3});
  expect_near(p[1], {1, 3, 3});
  expect_near(p[2], {3, 3, 3});
  // Frame 1 (rest) in centimetres, y up: (x, y, z)_bvh -> (z, x, y)_world.
  p.clear();
  forward_kinematics_frame(b, 1, 0.01, UpAxis::y, p);
  expect_near(p[1], {0, 0.01, 0});
  expect_near(p[2], {0.02, 0.01, 0});
  // Whole-clip FK agrees with the per-frame one.
  const auto all = forward_kinematics(b, 1.0, UpAxis::z);
  ASSERT_EQ(all.size(), 6u);
  expect_near(all[2], {3, 3, 3});
  EXPECT_THROW(forward_kinematics_frame(b, 2, 1.0, UpAxis::z, p), Error);
}

TEST(Fk, RotationsComposeInChannelOrder) {
  // Same angles, other order: Arm X then Z vs Z then X (Arm has Xrotation
  // 90 and Zrotation 90). Tip offset (0,0,2) from Arm.
  std::string xz = replace_all(kTwoJoint, "CHANNELS 3 Xrotation Yrotation Zrotation",
                               "CHANNELS 3 Xrotation Zrotation Yrotation");
  std::string zx = replace_all(kTwoJoint, "CHANNELS 3 Xrotation Yrotation Zrotation",
                               "CHANNELS 3 Zrotation Xrotation Yrotation");
  xz = replace_all(xz, "1 2 3 90 0 0 90 0 0", "0 0 0 0 0 0 90 90 0");
  zx = replace_all(zx, "1 2 3 90 0 0 90 0 0", "0 0 0 0 0 0 90 90 0");
  std::vector<Eigen::Vector3d> a, c;
  forward_kinematics_frame(parse_bvh(xz, "xz.bvh"), 0, 1.0, UpAxis::z, a);
  forward_kinematics_frame(parse_bvh(zx, "zx.bvh"), 0, 1.0, UpAxis::z, c);
  // Rx90 Rz90 (0,0,2) = Rx90 (0,0,2) = (0,-2,0); Rz90 Rx90 (0,0,2) = Rz90 (0,-2,0) = (2,0,0).
  expect_near(a[2] - a[1], {0, -2, 0});
  expect_near(c[2] - c[1], {2, 0, 0});
}

TEST(BvhWrite, RoundTripKeepsWorldPositions) {
  // A rig with mixed channel orders and random motion.
  Bvh b = read_bvh(kSmall);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-179, 179), pos(-50, 50);
  const Channel orders[6][3] = {{Channel::Xrotation, Channel::Yrotation, Channel::Zrotation},
                                {Channel::Xrotation, Channel::Zrotation, Channel::Yrotation},
                                {Channel::Yrotation, Channel::Xrotation, Channel::Zrotation},
                                {Channel::Yrotation, Channel::Zrotation, Channel::Xrotation},
                                {Channel::Zrotation, Channel::Xrotation, Channel::Yrotation},
                                {Channel::Zrotation, Channel::Yrotation, Channel::Xrotation}};
  for (std::size_t j = 1; j < b.joints.size(); ++j)
    b.joints[j].channels.assign(orders[j % 6], orders[j % 6] + 3);
  for (int f = 0; f < b.frames(); ++f)
    for (int c = 0; c < b.channel_count; ++c)
      b.values[std::size_t(f) * b.channel_count + c] = c < 3 ? pos(rng) : angle(rng);

  const Bvh back = parse_bvh(format_bvh(b), "back.bvh");
  ASSERT_EQ(back.frames(), b.frames());
  ASSERT_EQ(back.joints.size(), b.joints.size());
  EXPECT_NEAR(back.frame_time, b.frame_time, 1e-12);
  for (double scale : {0.01, 1.0}) {
    const auto p0 = forward_kinematics(b, scale, UpAxis::y);
    const auto p1 = forward_kinematics(back, scale, UpAxis::y);
    double worst = 0;
    for (std::size_t i = 0; i < p0.size(); ++i) worst = std::max(worst, (p0[i] - p1[i]).norm());
    EXPECT_LT(worst, 1e-4) << "scale " << scale;
  }
}

TEST(BvhWrite, WritesAtomicallyAndRefusesToOverwrite) {
  const fs::path dir =
      fs::temp_directory_path() / ("ptnet_bvh_write_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "out.bvh").string();
  const Bvh b = parse_bvh(kTwoJoint, "two.bvh");
  write_bvh(b, path, false);
  // (read_text_file, not read_bvh: a file read as an input may not be replaced by the same run)
  EXPECT_EQ(parse_bvh(read_text_file(path), path).values, b.values);
  try {
    write_bvh(b, path, false);
    FAIL() << "overwrote without force";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": exists; pass force to overwrite");
    EXPECT_EQ(e.kind(), ErrorKind::exists);
  }
  EXPECT_NO_THROW(write_bvh(b, path, true));
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left behind
  fs::remove_all(dir);
}

TEST(Units, ParseAndNames) {
  EXPECT_EQ(parse_units("auto"), Units::automatic);
  EXPECT_EQ(parse_units("CM"), Units::cm);
  EXPECT_EQ(parse_units("cmu"), Units::cmu);
  EXPECT_STREQ(units_name(Units::in), "in");
  EXPECT_EQ(parse_up_axis("z"), UpAxis::z);
  EXPECT_THROW(parse_units("feet"), Error);
  EXPECT_THROW(parse_up_axis("x"), Error);
  const Bvh b = read_bvh(kSmall);
  EXPECT_DOUBLE_EQ(metres_per_unit(b, Units::mm, UpAxis::y), 0.001);
  EXPECT_NEAR(metres_per_unit(b, Units::cmu, UpAxis::y), 0.05644, 1e-5);
}

TEST(Units, DetectedFromTheFirstFrameHeight) {
  const Bvh cm = read_bvh(kSmall);  // 170 cm tall, T-pose in frame 0
  EXPECT_DOUBLE_EQ(metres_per_unit(cm, Units::automatic, UpAxis::y), 0.01);
  EXPECT_DOUBLE_EQ(metres_per_unit(scaled(cm, 0.01), Units::automatic, UpAxis::y), 1.0);
  EXPECT_DOUBLE_EQ(metres_per_unit(scaled(cm, 10), Units::automatic, UpAxis::y), 0.001);
  EXPECT_DOUBLE_EQ(metres_per_unit(scaled(cm, 1 / 2.54), Units::automatic, UpAxis::y), 0.0254);
  EXPECT_NEAR(metres_per_unit(scaled(cm, 1 / 5.644), Units::automatic, UpAxis::y), 0.05644, 1e-5);
}

TEST(Resample, KeepsSourceSamplesAndSlerpsHalfway) {
  // Root only: 6 channels, ZYX. 10 fps -> 20 fps.
  const char* text =
      "HIERARCHY\nROOT R\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation "
      "Yrotation Xrotation\n"
      " End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 3\nFrame Time: 0.1\n"
      "0 0 0 10 20 30\n"
      "2 4 6 170 -40 60\n"
      "4 0 0 -170 0 0\n";
  const Bvh b = parse_bvh(text, "r.bvh");
  const Bvh r = resample(b, 20);
  ASSERT_EQ(r.frames(), 5);
  EXPECT_NEAR(r.fps(), 20, 1e-12);
  for (int f = 0; f < 3; ++f)
    for (int c = 0; c < 6; ++c) EXPECT_EQ(r.frame(2 * f)[c], b.frame(f)[c]) << f << " " << c;
  // Halfway: positions linear, rotation = slerp(0.5).
  for (int f = 0; f < 2; ++f) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(r.frame(2 * f + 1)[c], 0.5 * (b.frame(f)[c] + b.frame(f + 1)[c]), 1e-12);
    const Eigen::Quaterniond want = rotation_of(b, 0, f).slerp(0.5, rotation_of(b, 0, f + 1));
    EXPECT_LT(rotation_of(r, 0, 2 * f + 1).angularDistance(want), 1e-9);
  }
  // Shortest arc: 170 deg -> -170 deg about z passes through 180, not 0.
  const Eigen::Quaterniond mid = rotation_of(r, 0, 3);
  const Eigen::Quaterniond a = rotation_of(b, 0, 1), c = rotation_of(b, 0, 2);
  EXPECT_NEAR(mid.angularDistance(a), 0.5 * a.angularDistance(c), 1e-9);
  // 120 -> 30 Hz keeps every fourth frame exactly.
  Bvh fast = b;
  fast.frame_time = 1.0 / 120;
  fast.values.clear();
  for (int f = 0; f < 9; ++f)
    for (int c = 0; c < 6; ++c) fast.values.push_back(f * 3.0 + c);
  const Bvh slow = resample(fast, 30);
  ASSERT_EQ(slow.frames(), 3);
  for (int f = 0; f < 3; ++f) EXPECT_EQ(slow.frame(f)[0], fast.frame(4 * f)[0]);
}

TEST(Resample, EulerAnglesRewrittenInEveryChannelOrder) {
  const char* orders[] = {"Xrotation Yrotation Zrotation", "Xrotation Zrotation Yrotation",
                          "Yrotation Xrotation Zrotation", "Yrotation Zrotation Xrotation",
                          "Zrotation Xrotation Yrotation", "Zrotation Yrotation Xrotation"};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(-180, 180);
  for (const char* order : orders) {
    std::string text =
        std::string("HIERARCHY\nROOT R\n{\n OFFSET 0 0 0\n CHANNELS 3 ") + order +
        "\n End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n";
    for (int f = 0; f < 2; ++f)
      text += std::to_string(angle(rng)) + " " + std::to_string(angle(rng) / 2) + " " +
              std::to_string(angle(rng)) + "\n";
    const Bvh b = parse_bvh(text, "o.bvh");
    const Bvh r = resample(b, 40);  // 0, 0.25, 0.5, 0.75, 1
    ASSERT_EQ(r.frames(), 5);
    for (int k = 1; k < 4; ++k) {
      const Eigen::Quaterniond want = rotation_of(b, 0, 0).slerp(k / 4.0, rotation_of(b, 0, 1));
      EXPECT_LT(rotation_of(r, 0, k).angularDistance(want), 1e-9) << order << " t=" << k / 4.0;
    }
  }
}

TEST(Canonical, NamesAndParents) {
  EXPECT_STREQ(joint_name(kPelvis), "pelvis");
  EXPECT_STREQ(joint_name(kLeftToe), "left_toe");
  EXPECT_STREQ(joint_name(kRightWrist), "right_wrist");
  EXPECT_EQ(joint_parent(kPelvis), -1);
  EXPECT_EQ(joint_parent(kLeftKnee), kLeftHip);
  EXPECT_EQ(joint_parent(kRightShoulder), kChest);
  EXPECT_EQ(joint_parent(kHead), kNeck);
  for (int k = 1; k < kJointCount; ++k) EXPECT_LT(joint_parent(k), k);
}

TEST(Canonical, MapsEveryNamingScheme) {
  const Bvh cmu = read_bvh(kSmall);
  const auto want = map_canonical(cmu);
  EXPECT_EQ(cmu.joints[std::size_t(want[kPelvis])].name, "Hips");
  EXPECT_EQ(cmu.joints[std::size_t(want[kSpine])].name, "Spine");
  EXPECT_EQ(cmu.joints[std::size_t(want[kChest])].name, "Spine1");
  EXPECT_EQ(cmu.joints[std::size_t(want[kLeftShoulder])].name, "LeftArm");
  EXPECT_EQ(cmu.joints[std::size_t(want[kRightToe])].name, "RightToeBase");

  using Renames = std::vector<std::pair<std::string, std::string>>;
  auto renamed = [&](const Renames& names, const std::string& prefix) {
    Bvh b = cmu;
    for (BvhJoint& j : b.joints) {
      for (const auto& [from, to] : names) {
        if (j.name == from) {
          j.name = to;
          break;
        }
        for (const char* side : {"Left", "Right"})
          if (from.find("Left") == 0 && j.name == side + from.substr(4)) {
            j.name = replace_all(to, "L_", side[0] == 'L' ? "L_" : "R_");
            break;
          }
      }
      j.name = prefix + j.name;
    }
    return b;
  };
  const Renames smpl = {
      {"Hips", "Pelvis"},         {"LeftUpLeg", "L_Hip"},       {"LeftLeg", "L_Knee"},
      {"LeftFoot", "L_Ankle"},    {"LeftToeBase", "L_Foot"},    {"Spine", "Spine1"},
      {"Spine1", "Spine3"},       {"LeftShoulder", "L_Collar"}, {"LeftArm", "L_Shoulder"},
      {"LeftForeArm", "L_Elbow"}, {"LeftHand", "L_Wrist"}};
  const Renames cc = {{"Hips", "CC_Base_Hip"},
                      {"Spine", "CC_Base_Spine01"},
                      {"Spine1", "CC_Base_Spine02"},
                      {"Neck", "CC_Base_NeckTwist01"},
                      {"Head", "CC_Base_Head"},
                      {"LeftUpLeg", "CC_Base_L_Thigh"},
                      {"LeftLeg", "CC_Base_L_Calf"},
                      {"LeftFoot", "CC_Base_L_Foot"},
                      {"LeftToeBase", "CC_Base_L_ToeBase"},
                      {"LeftShoulder", "CC_Base_L_Clavicle"},
                      {"LeftArm", "CC_Base_L_Upperarm"},
                      {"LeftForeArm", "CC_Base_L_Forearm"},
                      {"LeftHand", "CC_Base_L_Hand"}};
  struct Case {
    const char* scheme;
    Bvh bvh;
  };
  Bvh lower = cmu;
  for (BvhJoint& j : lower.joints)
    for (char& ch : j.name) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  const Renames canonical = {{"Hips", "pelvis"},        {"Spine", "spine"},
                             {"Spine1", "chest"},       {"Neck", "neck"},
                             {"Head", "head"},          {"LeftUpLeg", "L_hip"},
                             {"LeftLeg", "L_knee"},     {"LeftFoot", "L_ankle"},
                             {"LeftToeBase", "L_toe"},  {"LeftShoulder", "L_clavicle"},
                             {"LeftArm", "L_shoulder"}, {"LeftForeArm", "L_elbow"},
                             {"LeftHand", "L_wrist"}};
  Bvh ours = renamed(canonical, "");
  for (BvhJoint& j : ours.joints) {
    if (j.name.rfind("L_", 0) == 0) j.name = "left_" + j.name.substr(2);
    if (j.name.rfind("R_", 0) == 0) j.name = "right_" + j.name.substr(2);
  }
  const Case cases[] = {{"ptnet canonical", ours},
                        {"mixamo", renamed({}, "mixamorig:")},
                        {"humanik", renamed({}, "Character1_")},
                        {"lowercase", lower},
                        {"smpl", renamed(smpl, "")},
                        {"character creator", renamed(cc, "")}};
  for (const Case& c : cases) {
    std::array<int, kJointCount> got{};
    ASSERT_NO_THROW(got = map_canonical(c.bvh)) << c.scheme;
    for (int k = 0; k < kJointCount; ++k)
      EXPECT_EQ(got[std::size_t(k)], want[std::size_t(k)])
          << c.scheme << " " << joint_name(k) << " -> "
          << c.bvh.joints[std::size_t(got[std::size_t(k)])].name;
  }
}

TEST(Canonical, UnmappableListsMissingAndFound) {
  Bvh b = read_bvh(kSmall);
  b.joints[std::size_t(b.find("LeftLeg"))].name = "Shin_L_Thing";
  try {
    map_canonical(b);
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos);
    EXPECT_NE(
        m.find(kSmall +
               ": cannot map to the canonical joints: missing left_knee, left_ankle, left_toe;"),
        std::string::npos)
        << m;
    EXPECT_NE(m.find("joints found: Hips LeftUpLeg Shin_L_Thing"), std::string::npos) << m;
  }
}

// A rate within 1e-4 of the file's is the file's rate written with a few
// digits (0.0333333 s): the frames as they are, at exactly that rate. A
// rate that is not one (NaN, infinity, beyond the range) is an error, not
// the file's own rate.
TEST(Resample, TheRateAskedForIsTheMotionsOrAnError) {
  const Bvh b = read_bvh(kSmall);
  MotionOptions o;
  o.keep_tpose = true;
  EXPECT_EQ(motion_from_bvh(b, o).fps, 30);
  EXPECT_EQ(motion_from_bvh(b, o).size(), 4);
  o.fps = 0;
  EXPECT_EQ(motion_from_bvh(b, o).fps, b.fps());
  for (const double fps : {double(NAN), double(INFINITY), -double(INFINITY), 5000.0}) {
    o.fps = fps;
    try {
      motion_from_bvh(b, o);
      ADD_FAILURE() << fps << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "fps: " + number_text(fps) + " is not in (0, 4000]");
    }
  }
}

TEST(TPose, DetectedAndDroppedByDefault) {
  const Bvh b = read_bvh(kSmall);
  const auto map = map_canonical(b);
  EXPECT_TRUE(is_tpose(b, 0, map, 0.01, UpAxis::y));
  for (int f = 1; f < b.frames(); ++f) EXPECT_FALSE(is_tpose(b, f, map, 0.01, UpAxis::y));
  MotionOptions o;
  const Motion m = motion_from_bvh(b, o);
  EXPECT_EQ(m.name, "tpose_cmu_small");
  ASSERT_EQ(m.size(), 3);
  EXPECT_NEAR(m.fps, 30, 1e-3);
  // Arms down in every kept frame; root advanced 2 cm per frame along z_bvh = x_world.
  EXPECT_LT(m.frames[0][kLeftWrist].z(), m.frames[0][kLeftShoulder].z() - 0.5);
  EXPECT_NEAR(m.frames[0][kPelvis].x(), 0.02, 1e-9);
  o.keep_tpose = true;
  EXPECT_EQ(motion_from_bvh(b, o).size(), 4);
}

TEST(Measure, CanonicalSkeletonStandsOnTheFloorAndMeasuresItsHeight) {
  MotionOptions o;
  o.keep_tpose = true;
  const Motion m = load_motion(kSmall, o);
  const Pose& p = m.frames[0];
  // (1e-4: the team notes round the foot offsets to 4 decimals of H; the
  // code takes them from anthropometry.hpp, e.g. toe 0.152 * 0.52 = 0.07904 H.)
  EXPECT_NEAR(lowest_foot_z(p), 0.0, 1e-4);
  EXPECT_NEAR(standing_height(m), 1.70, 1e-4);
  // World axes: +x forward (toes ahead of ankles), +y left, z up.
  EXPECT_GT(p[kLeftToe].x(), p[kLeftAnkle].x() + 0.1);
  EXPECT_GT(p[kLeftHip].y(), p[kRightHip].y());
  EXPECT_NEAR(p[kHead].z(), 0.870 * 1.70, 1e-4);
  // Lifting the heel 30 degrees about the toe joint: the toe tip (pitched
  // down) is the lowest point, below the toe joint by more than at rest.
  Pose q = p;
  const double H = 1.70;
  const Eigen::AngleAxisd pitch(30 * M_PI / 180, Eigen::Vector3d::UnitY());  // toes down, heel up
  q[kLeftAnkle] = q[kLeftToe] + pitch * (p[kLeftAnkle] - p[kLeftToe]);
  q[kRightAnkle] = q[kLeftAnkle] + Eigen::Vector3d(0, -0.2, 0);
  q[kRightToe] = q[kLeftToe] + Eigen::Vector3d(0, -0.2, 0);
  const Eigen::Vector3d tip = q[kLeftToe] + pitch * Eigen::Vector3d(0.0395 * H, 0, -0.009 * H);
  EXPECT_LT(tip.z(), q[kLeftToe].z() - 0.009 * H);
  EXPECT_NEAR(lowest_foot_z(q), tip.z(), 1e-4);
  // Raising the whole pose raises the lowest point by the same amount.
  Pose up = p;
  for (auto& j : up) j.z() += 0.1;
  EXPECT_NEAR(lowest_foot_z(up) - lowest_foot_z(p), 0.1, 1e-12);
}
