// The simulator pinned (issue 41): simulate()'s output bytes and its
// per-frame trace (FrameTrace: per-foot force, heel / forefoot, cop_u, area;
// load, other, sink), as FNV-1a 64 digests, on fixed clips x bodies x
// options. Any change to what the simulator computes, however small, changes
// a digest: a refactoring must leave them all as they are.
//
// Clips: a procedural walk and range of motion (always), a kneeling sway
// built from the body (knee, hand and sole contact; always), two real CMU
// clips from the shared motion-capture folder (PTNET_SHARED_MOCAP,
// cmake/ptnet.cmake: a walk that leaves the mat; squats and jogging;
// skipped when the folder is absent) and their committed twins, which run
// in every clone: the synthetic treadmill walk of tests/data/gait
// (scripts/make-gait-trial.py) read as markers through a clips CSV with its
// static trial (the marker path, the static calibration, the belt found and
// removed; 2.8 m of walking, so it leaves the fixed mat as 002_01 does), and
// the same walk's lab positions written as a BVH file in the CMU clips'
// units (0.05644 m, y up) at 120 frames/s and read back through a clips CSV
// (the BVH reader, the units, the 120 -> 30 resampling, the belt found and
// removed on a BVH clip, as for 14_06). Bodies: a light short and a heavy
// tall one. Options: the defaults with sensor noise (seed 7); the mat
// following the body with an ideal sensor and 4 x 4 samples per cell; no
// moment balance with 2 x 2 samples and a 30 mm band. Each case runs
// simulate() without a trace (the fast paths) and with one (the same bytes
// are required) and digests both the pressure and the trace.
//
// The digests hold at every instruction-set level of
// scripts/check-numerics.sh (label numerics). The pressure digest is of the
// exact bytes. The trace is digested with each double rounded to float: its
// doubles end in libm's last bits (the load and the zero-moment point come
// through exp, the CoM acceleration's Gaussian filter; the motion and the
// soles' frames through sin, cos and atan2), and libm's FMA variants, which
// the script's default level turns off, differ from the others there by a
// few ulps (up to 7 in these cases; a float's ulp is 2^29 of them). Rounded
// to float, the trace is the same at every level, as the pressure is (a
// float already, where such a difference rounds away).
//
// Updating the digests, only when the physics changes on purpose:
//   PTNET_GOLDEN_PRINT=1 build/tests/sim_golden_test
// prints every case's line ({"case", "pressure digest", "trace digest"});
// replace the kGolden table with them, and state in the commit body which
// cases changed and why (the physics change that moved them). A failing case
// prints its new line too. A digest change in a commit that does not state
// one is a regression.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <unistd.h>
#include <vector>

#include "core/hash.hpp"
#include "ptnet/body.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "sim_poses.hpp"

namespace ptnet {
namespace {

struct Golden {
  const char* name;      // clip/body/options
  const char* pressure;  // digest of the frames count and the kPa floats
  const char* trace;     // digest of every FrameTrace field, frame by frame
};

// clang-format off
const std::vector<Golden> kGolden = {
  {"walk/f150/default", "612cf55d1196b35e", "a2c75d2714e83140"},
  {"walk/f150/follow_ideal_s4", "a35de54b603617bf", "46eb7cd84413ab52"},
  {"walk/f150/nobalance_s2", "9dc521e0852a1476", "29a931373c3d7b6f"},
  {"walk/m196/default", "09904269b0dbbd8f", "dcea49fb84bf7f8d"},
  {"walk/m196/follow_ideal_s4", "33b9b9ced709fbfc", "d57298463d358c44"},
  {"walk/m196/nobalance_s2", "b356498f11adda55", "e3bf766a746bd4e2"},
  {"rom/f150/default", "8a395036e56cc49e", "8ac06c8582e28613"},
  {"rom/f150/follow_ideal_s4", "70784b278efe69ca", "4f18d10058f533f2"},
  {"rom/f150/nobalance_s2", "c0a7a357888e2cd0", "465dfb69002e29d1"},
  {"rom/m196/default", "18a3e9db581a93e4", "83f6b3420d8385f0"},
  {"rom/m196/follow_ideal_s4", "463b9b6501352474", "2d8a5c75edac17eb"},
  {"rom/m196/nobalance_s2", "df78a54c54c1bdd3", "21aa3904760275ab"},
  {"kneel/f150/default", "ef1c4471953612c9", "dc2563d82ea023ac"},
  {"kneel/f150/follow_ideal_s4", "719ae775e4e3bbf7", "a62b0912c0ede3e0"},
  {"kneel/f150/nobalance_s2", "c537c6cd04d6380f", "c057c75e3e213370"},
  {"kneel/m196/default", "9799aed1bbf1e2ef", "64dac8597d220929"},
  {"kneel/m196/follow_ideal_s4", "3e1f81556d262d22", "03fb54434a7a36ae"},
  {"kneel/m196/nobalance_s2", "11738cdfc202b7fc", "a157f755a6bcc316"},
  {"002_01/f150/default", "3f7dc28a95d1a973", "b3e95fc3e4fdfe78"},
  {"002_01/f150/follow_ideal_s4", "0a19317eebc2e520", "d9370b9ce069ecd0"},
  {"002_01/f150/nobalance_s2", "956db7f8875d294b", "9fe20ca8858abacd"},
  {"002_01/m196/default", "3c09894353e1fd9c", "93d4463193fe1869"},
  {"002_01/m196/follow_ideal_s4", "f13f314f015b0c6c", "7e1ed370976a4327"},
  {"002_01/m196/nobalance_s2", "30ecee5798ea9e69", "b85777e808068473"},
  {"14_06/f150/default", "b50a7487de8a2bfc", "b98b6dbba8407b6c"},
  {"14_06/f150/follow_ideal_s4", "80a550377f5ef59b", "65da28ca57b99ca8"},
  {"14_06/f150/nobalance_s2", "85307071f2e645e0", "b6aa361357bee984"},
  {"14_06/m196/default", "268bb45cea4ee365", "ca2e19fdde66844d"},
  {"14_06/m196/follow_ideal_s4", "b1b823aa44228197", "88f1ad30bac1efb2"},
  {"14_06/m196/nobalance_s2", "c992b54d90b42d16", "37aca99578fba759"},
  {"trc_walk/f150/default", "6e61d592525392e3", "ce2921f98da96e62"},
  {"trc_walk/f150/follow_ideal_s4", "ac2a98261220dab8", "a15d5bc45ba9a9c9"},
  {"trc_walk/f150/nobalance_s2", "af1f35ef4335f5e7", "cdc51d9252736ccc"},
  {"trc_walk/m196/default", "b9be8d70de61271e", "a6a95b9751ab29a7"},
  {"trc_walk/m196/follow_ideal_s4", "7e04e9b55ee0bd39", "e47292f88629045e"},
  {"trc_walk/m196/nobalance_s2", "0e05e48e5ff14b52", "7460e624a44bae17"},
  {"bvh_treadmill/f150/default", "0c99e0984fd59a08", "8a070592d87c0d12"},
  {"bvh_treadmill/f150/follow_ideal_s4", "21a5a8a91bce14e2", "5bcba3e5fe7e8cff"},
  {"bvh_treadmill/f150/nobalance_s2", "dec32490bc42307b", "1a89dc7ee2844436"},
  {"bvh_treadmill/m196/default", "03f3c8a6039a7537", "28df56e25231df89"},
  {"bvh_treadmill/m196/follow_ideal_s4", "8b2d7525da4ccf9b", "ba7e272015462326"},
  {"bvh_treadmill/m196/nobalance_s2", "7df0142a654de829", "943375368c0ad835"},
};
// clang-format on

const std::vector<BodySpec> kBodies = {
    {"f150", Sex::female, 150, 48, "retargeted"},
    {"m196", Sex::male, 196, 104, "retargeted"},
};

struct Config {
  const char* name;
  std::function<void(SimOptions&)> set;
};
const std::vector<Config> kConfigs = {
    {"default", [](SimOptions& o) { o.seed = 7; }},
    {"follow_ideal_s4",
     [](SimOptions& o) {
       o.placement = Placement::follow;
       o.sensor = ideal_sensor();
       o.subsamples = 4;
     }},
    {"nobalance_s2",
     [](SimOptions& o) {
       o.balance_moments = false;
       o.sensor = ideal_sensor();
       o.subsamples = 2;
       o.compliance_m = 0.030;
     }},
};

std::string pressure_digest(const PressureSequence& s) {
  Fnv1a h;
  const std::int64_t frames = s.frames();
  h.add(&frames, sizeof frames).add(s.kpa.data(), s.kpa.size() * sizeof(float));
  return h.hex();
}

// At float precision: the trace's doubles end in libm's last bits (see the
// top), the pressure's floats do not.
std::string trace_digest(const std::vector<FrameTrace>& trace) {
  Fnv1a h;
  auto add = [&](double v) {
    const float f = float(v);
    h.add(&f, sizeof f);
  };
  for (const FrameTrace& t : trace) {
    for (const FootLoad& f : t.foot) {
      add(f.force_n), add(f.heel_n), add(f.forefoot_n), add(f.cop_u), add(f.area_m2);
    }
    add(t.load_n), add(t.other_n), add(t.sink_m);
  }
  return h.hex();
}

bool print_mode() {
  const char* v = std::getenv("PTNET_GOLDEN_PRINT");
  return v && *v && std::string(v) != "0";
}

// Frames in which contact off the mat or by other body parts than the soles
// carries load: what a case covers.
struct Coverage {
  int off_mat = 0;  // the frame reads 0 while the body carries load
  int other = 0;    // other_n > 0 (knees, hands, ...)
  int both_feet = 0;
};

// Simulates one case with the given placement and compares its digests with
// kGolden.
Coverage check_case(const std::string& name, const Motion& motion, const Body& body,
                    const SimOptions& o, const MotionPlacement& place) {
  const PressureSequence fast = simulate(motion, body, o, place, nullptr);
  std::vector<FrameTrace> trace;
  const PressureSequence traced = simulate(motion, body, o, place, &trace);
  Coverage cover;
  if (fast.kpa.size() != traced.kpa.size()) {
    ADD_FAILURE() << name << ": the trace changed the frame count";
    return cover;
  }
  for (int f = 0; f < fast.frames(); ++f) {
    const FrameTrace& x = trace[std::size_t(f)];
    const bool zero = std::all_of(fast.frame(f), fast.frame(f) + fast.mat.cells(),
                                  [](float v) { return v == 0; });
    cover.off_mat += zero && x.foot[0].force_n + x.foot[1].force_n + x.other_n > 0;
    cover.other += x.other_n > 0;
    cover.both_feet += x.foot[0].force_n > 0 && x.foot[1].force_n > 0;
  }
  EXPECT_EQ(0, std::memcmp(fast.kpa.data(), traced.kpa.data(), fast.kpa.size() * sizeof(float)))
      << name << ": the trace changed the pressure";
  const std::string p = pressure_digest(fast), t = trace_digest(trace);
  const std::string line = "{\"" + name + "\", \"" + p + "\", \"" + t + "\"},";
  if (print_mode()) std::printf("  %s\n", line.c_str());
  const Golden* g = nullptr;
  for (const Golden& x : kGolden)
    if (name == x.name) g = &x;
  if (!g) {
    ADD_FAILURE() << name << ": no digest in kGolden; add\n  " << line;
    return cover;
  }
  EXPECT_EQ(p, g->pressure) << name << ": pressure changed; if on purpose (see the top): " << line;
  EXPECT_EQ(t, g->trace) << name << ": trace changed; if on purpose (see the top): " << line;
  return cover;
}

// Every body x options of a source motion: retargeted onto the body, placed
// once (on the source) and scaled to the copy, as simulate_dataset does.
Coverage check_clip(const std::string& clip, const Motion& source) {
  Coverage all;
  for (const BodySpec& spec : kBodies) {
    const Body body(spec);
    const Motion m = retarget(source, spec.height_cm);
    for (const Config& c : kConfigs) {
      SimOptions o;
      c.set(o);
      const Coverage x = check_case(clip + "/" + spec.id + "/" + c.name, m, body, o,
                                    place_copy(source, spec.height_cm, o));
      all.off_mat += x.off_mat, all.other += x.other, all.both_feet += x.both_feet;
    }
  }
  return all;
}

Motion procedural(Category category, int performer, double seconds) {
  GenerateOptions g;
  g.category = category;
  g.performer = performer;
  g.seconds = seconds;
  g.seed = 41;
  return generate_motion(g);
}

// The kneeling lunge of kneel_pose swaying (1 s at 30 fps): the load and the
// zero-moment point move with the swing, the knee and hand stay down.
Motion kneel_sway(const Body& body) {
  Motion m;
  m.name = "kneel_sway";
  m.fps = 30;
  const Pose pose = test::kneel_pose(body);
  for (int t = 0; t < 30; ++t) {
    const double a = 2 * M_PI * t / 30;
    Pose p = pose;
    for (auto& j : p)
      j += Eigen::Vector3d(0.03 * std::sin(a), 0.02 * std::cos(a), 0.002 * std::sin(2 * a));
    m.frames.push_back(p);
  }
  return m;
}

TEST(SimGolden, EmbeddedClips) {
  EXPECT_GT(check_clip("walk", procedural(Category::walking, 2, 6)).both_feet, 0);
  check_clip("rom", procedural(Category::rom, 1, 6));
  // Built on each body (no retargeting): its capsules' radii set the pose.
  for (const BodySpec& spec : kBodies) {
    const Body body(spec);
    const Motion m = kneel_sway(body);
    for (const Config& c : kConfigs) {
      SimOptions o;
      c.set(o);
      const Coverage x =
          check_case("kneel/" + spec.id + "/" + c.name, m, body, o, place_motion(m, o));
      EXPECT_EQ(x.other, m.size()) << "the knee and the hand carry load in every frame";
    }
  }
}

TEST(SimGolden, RealClips) {
  const std::string mocap = PTNET_SHARED_MOCAP;
  if (!std::filesystem::exists(mocap + "/clips.csv"))
    GTEST_SKIP() << mocap
                 << " not found (the shared CMU clips): the real clips' digests are not checked";
  for (const char* file : {"002_01.bvh", "14_06.bvh"}) {
    const std::vector<ClipSource> clips =
        clips_from_files({mocap + "/" + file}, mocap + "/clips.csv", {});
    ASSERT_EQ(clips.size(), 1u) << file;
    const Coverage x = check_clip(clips[0].meta.motion_id, load_clip(clips[0], 30));
    if (std::string(file) == "002_01.bvh")
      EXPECT_GT(x.off_mat, 0) << "the walk leaves the fixed mat";
  }
}

// The committed trial as a clip of a clips CSV (absolute paths), loaded as
// simulate_dataset loads it.
Motion clip_of_csv(const std::string& dir, const std::string& file, const std::string& csv_text) {
  const std::string csv = dir + "/" + file + ".csv";
  std::ofstream(csv) << csv_text;
  const std::vector<ClipSource> clips = clips_from_files({dir + "/" + file}, csv, {});
  EXPECT_EQ(clips.size(), 1u) << file;
  return load_clip(clips.at(0), 30);
}

// The BVH of `m` (canonical skeleton, centimetres) in units of `metres` m.
Bvh in_units(Bvh b, double metres) {
  const double k = 0.01 / metres;
  for (BvhJoint& j : b.joints) {
    j.offset *= k;
    j.end_site *= k;
    for (std::size_t c = 0; c < j.channels.size(); ++c)
      if (j.channels[c] == Channel::Xposition || j.channels[c] == Channel::Yposition ||
          j.channels[c] == Channel::Zposition)
        for (int f = 0; f < b.frames(); ++f)
          b.values[std::size_t(f) * std::size_t(b.channel_count) + std::size_t(j.first_channel) + c] *= k;
  }
  return b;
}

double pelvis_travel(const Motion& m) {
  return (m.frames.back()[kPelvis] - m.frames.front()[kPelvis]).head<2>().norm();
}

TEST(SimGolden, CommittedTwinsOfTheRealClips) {
  const std::string gait = std::string(PTNET_TEST_DATA) + "/gait";
  const std::string tmp =
      (std::filesystem::temp_directory_path() / ("ptnet_golden_" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(tmp);
  std::filesystem::copy_file(gait + "/walk.trc", tmp + "/walk.trc");
  // The marker file, its static trial named in the clips CSV.
  const Motion trc = clip_of_csv(tmp, "walk.trc",
                                 "file,subject,category,take,static\nwalk.trc,s1,walking,1," + gait +
                                     "/walk_static.trc\n");
  EXPECT_GT(pelvis_travel(trc), 2.5) << "the belt removed, the body walks 2.8 m";
  const Coverage walk = check_clip("trc_walk", trc);
  EXPECT_GT(walk.off_mat, 0) << "the walk leaves the fixed mat";
  EXPECT_GT(walk.both_feet, 0);
  // The same walk's lab positions (the belt kept) at 120 frames/s, as a CMU
  // BVH file: 0.05644 m units, y up.
  MotionOptions o;
  o.fps = 120;
  o.remove_belt = false;
  o.static_markers = gait + "/walk_static.trc";
  const Motion lab = retarget(motion_from_trc(read_trc(gait + "/walk.trc"), o), 175);
  EXPECT_LT(pelvis_travel(lab), 0.2) << "on the treadmill the pelvis stays";
  write_bvh(in_units(motion_to_bvh(lab), 0.05644), tmp + "/treadmill.bvh", false);
  const Motion bvh = clip_of_csv(tmp, "treadmill.bvh",
                                 "file,subject,category,take,metres_per_unit,up\ntreadmill.bvh,s1,walking,1,0.05644,y\n");
  EXPECT_GT(pelvis_travel(bvh), 2.5) << "the belt found and removed on a BVH clip";
  check_clip("bvh_treadmill", bvh);
  std::filesystem::remove_all(tmp);
}

}  // namespace
}  // namespace ptnet
