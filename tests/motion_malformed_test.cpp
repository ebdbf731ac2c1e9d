// Every malformed BVH fixture (tests/data/malformed) is rejected with its
// own one-line error naming the file, the line, what was expected and what
// was found.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

namespace {

const std::string kDir = std::string(PTNET_TEST_DATA) + "/malformed/";

struct Case {
  const char* file;
  const char* message;  // after "<path>:"
};

const Case kCases[] = {
    {"empty.bvh", "1: expected HIERARCHY, found an empty file"},
    {"no_hierarchy.bvh", "1: expected HIERARCHY, found ROOT"},
    {"truncated_hierarchy.bvh", "10: expected JOINT, End Site or }, found end of file"},
    {"extra_closing_brace.bvh", "16: expected MOTION, found }"},
    {"missing_closing_brace.bvh", "15: expected JOINT, End Site or }, found MOTION"},
    {"unknown_channel.bvh", "9: expected a channel name (X|Y|Z + position|rotation), found Xrot"},
    {"bad_channel_count.bvh", "9: expected a channel count of 0, 3 or 6, found 4"},
    {"too_few_channel_names.bvh",
     "10: expected a channel name (X|Y|Z + position|rotation), found End"},
    {"short_frame_line.bvh", "20: expected 9 values, found 8"},
    {"crlf_short_frame_line.bvh", "20: expected 9 values, found 8"},
    {"long_frame_line.bvh", "19: expected 9 values, found 10"},
    {"non_numeric_value.bvh", "19: expected a number, found abc"},
    {"nan_value.bvh", "20: expected a finite number, found nan"},
    {"inf_value.bvh", "19: expected a finite number, found -inf"},
    {"frames_more_than_lines.bvh", "21: expected 3 frame lines (Frames: 3), found 2"},
    {"frames_fewer_than_lines.bvh", "20: expected 1 frame line (Frames: 1), found more"},
    {"zero_frame_time.bvh", "18: expected a positive Frame Time (s), found 0"},
    {"negative_frame_time.bvh", "18: expected a positive Frame Time (s), found -0.033333"},
    {"missing_motion.bvh", "16: expected MOTION, found end of file"},
    {"missing_offset.bvh", "8: expected OFFSET, found CHANNELS"},
    {"bad_offset_number.bvh", "8: expected a number (OFFSET), found 1O"},
    {"duplicate_joint_name.bvh", "6: expected a joint name not used before, found Hips again"},
    {"zero_frames.bvh", "17: expected a frame count of at least 1, found 0"},
    {"missing_frame_time.bvh", "18: expected Frame Time:, found 0"},
};

}  // namespace

TEST(MotionMalformed, EachFixtureHasItsOwnMessage) {
  std::set<std::string> messages;
  for (const Case& c : kCases) {
    const std::string path = kDir + c.file;
    try {
      ptnet::read_bvh(path);
      ADD_FAILURE() << c.file << " was accepted";
    } catch (const ptnet::Error& e) {
      EXPECT_EQ(std::string(e.what()), path + ":" + c.message);
      messages.insert(std::string(e.what()).substr(path.size()));
    }
  }
  EXPECT_GE(messages.size(), 20u);  // distinct problems, distinct messages
}

TEST(MotionMalformed, EveryFixtureIsListed) {
  std::set<std::string> listed;
  for (const Case& c : kCases) listed.insert(c.file);
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(kDir)) {
    if (e.path().extension() != ".bvh") continue;  // marker files: motion_markers_test
    ++files;
    EXPECT_TRUE(listed.count(e.path().filename().string()))
        << e.path() << " has no expected message";
  }
  EXPECT_EQ(files, listed.size());
  EXPECT_GE(files, 12u);
}

TEST(MotionMalformed, ParseErrorsFromMemoryNameTheSource) {
  try {
    ptnet::parse_bvh("", "memory.bvh");
    FAIL();
  } catch (const ptnet::Error& e) {
    EXPECT_STREQ(e.what(), "memory.bvh:1: expected HIERARCHY, found end of file");
  }
  // Deep nesting is an error, not a stack overflow.
  std::string deep =
      "HIERARCHY\nROOT J0\n{\nOFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n";
  for (int i = 1; i < 5000; ++i) deep += "JOINT J" + std::to_string(i) + "\n{\nOFFSET 0 0 0\n";
  EXPECT_THROW(ptnet::parse_bvh(deep, "deep.bvh"), ptnet::Error);
  // An absurd Frame Time does not make resampling allocate gigabytes.
  std::string slow =
      "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 1e9\n1 2 3\n4 5 6\n";
  EXPECT_THROW(ptnet::resample(ptnet::parse_bvh(slow, "slow.bvh"), 30), ptnet::Error);
  // A huge Frames: claim does not allocate for it.
  std::string huge =
      "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n}\n"
      "MOTION\nFrames: 4000000000000\nFrame Time: 0.1\n1 2 3\n";
  try {
    ptnet::parse_bvh(huge, "huge.bvh");
    FAIL();
  } catch (const ptnet::Error& e) {
    EXPECT_STREQ(
        e.what(),
        "huge.bvh:11: expected 4000000000000 frame lines (Frames: 4000000000000), found 1");
  }
}

TEST(MotionMalformed, TruncationsAndMutationsNeverCrash) {
  std::ifstream in(std::string(PTNET_TEST_DATA) + "/bvh/tpose_cmu_small.bvh", std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string good = ss.str();
  ASSERT_GT(good.size(), 1000u);
  int accepted = 0, rejected = 0;
  auto attempt = [&](const std::string& text) {
    try {
      ptnet::Bvh b = ptnet::parse_bvh(text, "fuzz.bvh");
      ASSERT_EQ(b.values.size(), std::size_t(b.frames()) * std::size_t(b.channel_count));
      ++accepted;
      try {  // and the rest of the path: units, mapping, T-pose, resampling, FK
        const ptnet::Motion m = ptnet::motion_from_bvh(b, ptnet::MotionOptions{});
        ASSERT_GE(m.size(), 1);
      } catch (const ptnet::Error& e) {
        ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      }
    } catch (const ptnet::Error& e) {
      const std::string m = e.what();
      ASSERT_EQ(m.rfind("fuzz.bvh:", 0), 0u) << m;
      ASSERT_EQ(m.find('\n'), std::string::npos) << m;
      ++rejected;
    }
  };
  for (std::size_t n = 0; n < good.size(); n += 7) attempt(good.substr(0, n));
  std::mt19937_64 rng(11);
  const char alphabet[] = "0123456789.-+eE{} \t\r\nXYZrotainpsJOINTEndSite:";
  for (int i = 0; i < 3000; ++i) {
    std::string t = good;
    const int edits = 1 + int(rng() % 3);
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = rng() % t.size();
      switch (rng() % 3) {
        case 0:
          t[at] = alphabet[rng() % (sizeof alphabet - 1)];
          break;
        case 1:
          t.erase(at, 1 + rng() % 8);
          break;
        default:
          t.insert(at, 1, alphabet[rng() % (sizeof alphabet - 1)]);
          break;
      }
    }
    attempt(t);
  }
  EXPECT_GT(rejected, 1000);
  EXPECT_GT(accepted, 10);  // harmless edits (a digit changed) still parse
}
