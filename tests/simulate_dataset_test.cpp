// simulate_dataset() and the clip lists behind `ptnet simulate`: the file
// does not depend on threads or chunking; sequence metadata; clips CSV
// parsing and its one-line errors; category guesses.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "data/data_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "data_test_util.hpp"

namespace fs = std::filesystem;

namespace ptnet {
namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

using testing_util::error_of;

class SimulateDataset : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ptnet_simulate_dataset_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

const std::vector<BodySpec> kBodies{{"f1", Sex::female, 158, 55, "retargeted"}, {"m1", Sex::male, 188, 90, "original"}};

TEST_F(SimulateDataset, SameFileWhateverThreadsAndChunks) {
  const auto clips = embedded_clips(1, 1, 2.0, 4);
  ASSERT_EQ(clips.size(), 4u);
  SimulateDatasetOptions a;
  a.seed = 9;
  a.threads = 1;
  a.chunk_jobs = 1;
  SimulateDatasetOptions b = a;
  b.threads = 2;
  b.chunk_jobs = 0;
  const auto sa = simulate_dataset(clips, kBodies, (dir_ / "a.h5").string(), a);
  simulate_dataset(clips, kBodies, (dir_ / "b.h5").string(), b);
  EXPECT_EQ(sa.sequences, 8);
  EXPECT_EQ(sa.frames, 8 * 60);
  EXPECT_EQ(slurp(dir_ / "a.h5"), slurp(dir_ / "b.h5"));

  const Dataset d = Dataset::open((dir_ / "a.h5").string());
  EXPECT_EQ(d.info().generator, "ptnet simulate");
  EXPECT_NE(d.info().config_json.find("\"seed\":9"), std::string::npos) << d.info().config_json;
  ASSERT_EQ(d.sequences().size(), 8u);
  const SequenceMeta& m = d.sequence("p1_walking_t1__m1");
  EXPECT_EQ(m.body_id, "m1");
  EXPECT_EQ(m.motion_id, "p1_walking_t1");
  EXPECT_EQ(m.performer, "P1");
  EXPECT_EQ(m.category, "walking");
  EXPECT_EQ(m.take, 1);
  EXPECT_EQ(m.source, "procedural:p1_walking_t1");
  EXPECT_EQ(m.frames, 60);
  EXPECT_EQ(d.body("m1").role, "original");

  // Refuses to overwrite; nothing left on error.
  EXPECT_EQ(error_of([&] { simulate_dataset(clips, kBodies, (dir_ / "a.h5").string(), a); }),
            (dir_ / "a.h5").string() + ": exists; pass force to overwrite");
  EXPECT_EQ(error_of([&] { simulate_dataset(clips, {}, (dir_ / "c.h5").string(), a); }),
            "simulate: no bodies to simulate on");
  EXPECT_FALSE(fs::exists(dir_ / "c.h5"));
}

TEST_F(SimulateDataset, ClipsCsvRowsAndErrors) {
  spit(dir_ / "w.bvh", "x");
  spit(dir_ / "clips.csv", "take,file,category,subject,up,metres_per_unit\n2,w.bvh,walking,7,z,0.01\n");
  const auto rows = read_clips_csv((dir_ / "clips.csv").string());
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].file, (dir_ / "w.bvh").string());
  EXPECT_EQ(rows[0].subject, "7");
  EXPECT_EQ(rows[0].take, 2);
  EXPECT_EQ(rows[0].up, "z");
  EXPECT_DOUBLE_EQ(rows[0].metres_per_unit, 0.01);
  const auto clips = clips_from_files({(dir_ / "w.bvh").string()}, (dir_ / "clips.csv").string(), {});
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].meta.motion_id, "w");
  EXPECT_EQ(clips[0].meta.performer, "7");
  EXPECT_EQ(clips[0].motion.up, UpAxis::z);
  EXPECT_DOUBLE_EQ(clips[0].motion.metres_per_unit, 0.01);

  const std::string csv = (dir_ / "bad.csv").string();
  spit(csv, "file,subject,category,take\nw.bvh,1,walking,x\n");
  EXPECT_EQ(error_of([&] { read_clips_csv(csv); }), csv + ":2: expected take as an integer in 1-1000000, found 'x'");
  spit(csv, "file,subject,category,take\nw.bvh,1,jogging,1\n");
  EXPECT_EQ(error_of([&] { read_clips_csv(csv); }),
            csv + ":2: expected category walking, rom, freestyle or acting, found 'jogging'");
  spit(csv, "file,subject,take\n");
  EXPECT_EQ(error_of([&] { read_clips_csv(csv); }),
            csv + ":1: expected a header with column category (file,subject,category,take[,metres_per_unit,up,marker_map,static]), "
                  "found 'file,subject,take'");
  spit(csv, "file,subject,category,take\ngone.bvh,1,walking,1\n");
  EXPECT_EQ(error_of([&] { read_clips_csv(csv); }), csv + ":2: clip file 'gone.bvh': no such file");
  // A FIFO is there, but no clip (before: "not found"; har-bench --mocap said so).
  ASSERT_EQ(::mkfifo((dir_ / "live.bvh").c_str(), 0600), 0);
  spit(csv, "file,subject,category,take\nlive.bvh,1,walking,1\n");
  EXPECT_EQ(error_of([&] { read_clips_csv(csv); }), csv + ":2: clip file 'live.bvh': is a FIFO, expected a regular file");
  fs::remove(dir_ / "live.bvh");

  // Without a CSV: stems must be unique across folders.
  fs::create_directories(dir_ / "a");
  fs::create_directories(dir_ / "b");
  spit(dir_ / "a" / "s_01.bvh", "x");
  spit(dir_ / "b" / "s_01.bvh", "x");
  EXPECT_NE(error_of([&] { clips_from_files({dir_.string() + "/a", dir_.string() + "/b"}, "", {}); })
                .find("motion id 's_01' also used by"),
            std::string::npos);
  const auto one = clips_from_files({(dir_ / "a").string()}, "", {});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].meta.performer, "s");
  EXPECT_EQ(one[0].meta.take, 1);
}

// A BVH's Frame Time is written with a few digits: 0.016667 is 59.9988 fps,
// .0083333 120.0005, 0.033333 30.0003. Such a clip is recorded at the rate
// it rounds, and every rate asked for is the dataset's, checked before any
// simulation (before the fix, --fps 60 on the first ended "fps 59.9988
// differs from the dataset's 60" once every sequence was simulated).
TEST_F(SimulateDataset, RoundedFrameTimesAreTheRatesTheyRound) {
  std::string bvh = slurp(std::string(PTNET_TEST_DATA) + "/bvh/tpose_cmu_small.bvh");
  const std::string motion = bvh.substr(bvh.find("Frames: 4"));
  const std::string frame = motion.substr(motion.rfind('\n', motion.size() - 2) + 1);  // the last line
  std::string frames;
  for (int i = 0; i < 60; ++i) frames += frame;
  bvh = bvh.substr(0, bvh.find("Frames: 4")) + "Frames: 64\nFrame Time: FT\n" +
        motion.substr(motion.find('\n', motion.find("Frame Time")) + 1) + frames;
  // Frame times as the corpora write them, and a marker system's 100 Hz.
  for (const char* frame_time : {"0.016667", ".0083333", "0.033333", "0.0166670", "0.01", "0.04", "0.02"}) {
    std::string text = bvh;
    text.replace(text.find("FT"), 2, frame_time);
    const fs::path file = dir_ / "clip.bvh";
    spit(file, text);
    for (const double fps : {25.0, 30.0, 50.0, 60.0, 100.0, 120.0}) {
      SCOPED_TRACE(std::string(frame_time) + " s at " + number_text(fps) + " fps");
      const auto clips = clips_from_files({file.string()}, "", {});
      EXPECT_EQ(load_clip(clips[0], fps).fps, fps);
      SimulateDatasetOptions o;
      o.fps = fps;
      o.threads = 1;
      const std::string out = (dir_ / (std::string(frame_time) + "_" + number_text(fps) + ".h5")).string();
      const std::string error = error_of([&] { simulate_dataset(clips, {kBodies[0]}, out, o); });
      EXPECT_EQ(error, "(no error)");
      if (error == "(no error)") EXPECT_EQ(Dataset::open(out).info().fps, fps);
    }
  }
}

TEST(ClipsAtSpeeds, EveryClipAtEverySpeedAndOneLineErrors) {
  const auto clips = embedded_clips(1, 1, 2.0, 4);
  const auto at = clips_at_speeds(clips, {1, 1.5});
  ASSERT_EQ(at.size(), 2 * clips.size());
  EXPECT_EQ(at[0].meta.motion_id, clips[0].meta.motion_id);  // speed 1: the clip as it was
  EXPECT_EQ(at[1].meta.motion_id, clips[0].meta.motion_id + "_x1.5");
  EXPECT_EQ(at[1].meta.source, clips[0].meta.source + " x1.5");
  EXPECT_EQ(at[1].speed, 1.5);
  EXPECT_EQ(at[1].meta.take, clips[0].meta.take);
  EXPECT_EQ(load_clip(at[1], kFps).size(), 40);  // 2 s played 1.5 x as fast
  EXPECT_EQ(error_of([&] { clips_at_speeds(clips, {}); }), "speeds: expected at least one speed");
  EXPECT_EQ(error_of([&] { clips_at_speeds(clips, {0.1}); }), "speeds: 0.1 is not in [0.25, 4]");
  EXPECT_EQ(error_of([&] { clips_at_speeds(clips, {1, 1}); }), "speeds: 1 given twice");
  // A speed is its label: before, 0.8 and 0.8000001 were both _x0.8 (refused
  // as "added twice" once simulated), 1.000001 was _x1.
  EXPECT_EQ(error_of([&] { clips_at_speeds(clips, {0.8, 0.8000001}); }),
            "speeds: 0.8000001 has more digits than its label _x0.8 shows (at most 6 significant digits)");
  EXPECT_EQ(error_of([&] { clips_at_speeds(clips, {1.000001}); }),
            "speeds: 1.000001 has more digits than its label _x1 shows (at most 6 significant digits)");
  EXPECT_EQ(clips_at_speeds(clips, {0.333333})[0].meta.motion_id, clips[0].meta.motion_id + "_x0.333333");
}

// A frame span keeps its frames on the recording's clock: the span's first
// frame is its start (the forces files' time column), at any speed.
TEST(ClipSpan, StartsAtItsFirstFrameOnTheRecordingsClock) {
  ClipSource clip = embedded_clips(1, 1, 3.0, 4)[0];
  clip.first_frame = 30;
  clip.end_frame = 60;
  const Motion m = load_clip(clip, kFps);
  EXPECT_EQ(m.size(), 30);
  EXPECT_DOUBLE_EQ(m.start_s, 30 / kFps);
  ClipSource fast = clips_at_speeds({clip}, {1.5})[0];
  const Motion f = load_clip(fast, kFps);
  EXPECT_EQ(f.size(), 20);  // frames 20-40 of the clip read at 20 fps
  EXPECT_DOUBLE_EQ(f.start_s, 30 / kFps);  // still frame 30 of the recording at 30 fps
}

// A clip a_x0.8.bvh beside a.bvh played at 0.8: one motion id for two
// clips, refused before any clip is read (before: "added twice" once every
// sequence was simulated).
TEST_F(SimulateDataset, ClipIdsAreUniqueBeforeAnyWork) {
  const std::string bvh = slurp(std::string(PTNET_TEST_DATA) + "/bvh/tpose_cmu_small.bvh");
  spit(dir_ / "a.bvh", bvh);
  spit(dir_ / "a_x0.8.bvh", bvh);
  const auto clips = clips_at_speeds(clips_from_files({(dir_ / "a.bvh").string(), (dir_ / "a_x0.8.bvh").string()},
                                                      "", {}),
                                     {1, 0.8});
  const std::string out = (dir_ / "x.h5").string();
  EXPECT_EQ(error_of([&] { simulate_dataset(clips, kBodies, out, {}); }),
            (dir_ / "a_x0.8.bvh").string() + ": motion id 'a_x0.8' is also that of " + (dir_ / "a.bvh").string() +
                " x0.8: every clip needs its own");
  EXPECT_FALSE(fs::exists(out));
  BodySpec b = kBodies[0];
  EXPECT_EQ(error_of([&] { simulate_dataset(clips_from_files({(dir_ / "a.bvh").string()}, "", {}), {b, b}, out, {}); }),
            "simulate: body id 'f1' given twice");
}

// Ids that name sequences (and their force files) are file names, and the
// clip's text is UTF-8, both known before any work (before: a body id "a/b"
// failed at the first write, once a chunk was simulated; a Latin-1 stem went
// into attributes HDF5 declares UTF-8).
TEST_F(SimulateDataset, IdsAreFileNamesAndTextIsUtf8BeforeAnyWork) {
  const auto clips = embedded_clips(1, 1, 2.0, 4);
  const std::string out = (dir_ / "x.h5").string();
  BodySpec b = kBodies[0];
  b.id = "a/b";
  EXPECT_EQ(error_of([&] { simulate_dataset(clips, {b}, out, {}); }),
            "simulate: body id 'a/b' holds '/': it names the body's sequences");
  auto latin1 = clips;
  latin1[0].meta.source = "caf\xe9.bvh";
  EXPECT_NE(error_of([&] { simulate_dataset(latin1, kBodies, out, {}); }).find("is not UTF-8"), std::string::npos);
  EXPECT_FALSE(fs::exists(out));
}

// The forces folder is checked before any work (before: found once the
// dataset was written): not the dataset's own path, no input replaced.
TEST_F(SimulateDataset, TheForcesFolderIsCheckedBeforeAnyWork) {
  const auto clips = embedded_clips(1, 1, 2.0, 4);
  SimulateDatasetOptions o;
  const std::string out = (dir_ / "x.h5").string();
  o.forces_dir = out;
  EXPECT_EQ(error_of([&] { simulate_dataset(clips, kBodies, out, o); }),
            "forces_dir: " + out + " is the dataset's own path (" + out + "): give the force files a folder of their own");
  EXPECT_FALSE(fs::exists(out));
}

TEST(SimulateDatasetCategories, FromNames) {
  EXPECT_EQ(category_from_name("/x/subject5_walk_fast.bvh"), "walking");
  EXPECT_EQ(category_from_name("Range_of_motion.bvh"), "rom");
  EXPECT_EQ(category_from_name("salsa_dance.bvh"), "freestyle");
  EXPECT_EQ(category_from_name("002_01.bvh"), "");
  GenerateOptions g;
  g.seconds = 6;
  EXPECT_EQ(category_from_motion(generate_motion(g)), "walking");
  g.category = Category::rom;
  EXPECT_EQ(category_from_motion(generate_motion(g)), "freestyle");
}

}  // namespace
}  // namespace ptnet
