// The stand-in for real recordings: its degraded sensor (gain spread, dead
// cells), the dataset it writes, and the mocap variant (one subject per CMU
// subject of ../shared/mocap and of the real-motion corpus ../shared/mocap-corpus).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "har/standin.hpp"
#include "ptnet/simulate_dataset.hpp"

using namespace ptnet;
using namespace ptnet::har;

TEST(HarStandin, GainMapIsSeededWithTheRequestedDeadCells) {
  StandinOptions o;
  const MatSpec mat;
  const auto a = standin_gain_map(mat, o), b = standin_gain_map(mat, o);
  EXPECT_EQ(a, b);
  EXPECT_EQ(std::count(a.begin(), a.end(), 0.0f), 22);  // 1 % of 2240 cells
  std::vector<float> live;
  for (float g : a)
    if (g > 0) live.push_back(g);
  std::nth_element(live.begin(), live.begin() + live.size() / 2, live.end());
  EXPECT_NEAR(live[live.size() / 2], 1.0, 0.03);  // log-normal median 1
  const auto [lo, hi] = std::minmax_element(live.begin(), live.end());
  EXPECT_LT(*lo, 0.75f);  // sigma 0.15 over 2218 cells reaches beyond +-2 sigma
  EXPECT_GT(*hi, 1.3f);
  o.seed = 2;
  EXPECT_NE(standin_gain_map(mat, o), a);
}

TEST(HarStandin, WritesSubjectsOnTheirOwnBodiesWithDeadCellsSilent) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("ptnet_har_standin_test_" + std::to_string(::getpid()) + ".h5")).string();
  StandinOptions o;
  o.subjects = 2;
  o.seconds = 2;
  o.threads = 1;
  write_standin(path, o, /*force=*/true);
  const Dataset d = Dataset::open(path);
  ASSERT_EQ(d.bodies().size(), 2u);
  EXPECT_EQ(d.bodies()[0].id, "s1");
  EXPECT_EQ(d.bodies()[1].role, "original");
  EXPECT_NE(d.bodies()[0].height_cm, d.bodies()[1].height_cm);
  EXPECT_NE(d.info().config_json.find("stand-in"), std::string::npos);
  ASSERT_EQ(d.sequences().size(), 8u);  // 2 subjects x 4 categories
  const auto gain = standin_gain_map(d.info().mat, o);
  double total = 0;
  for (const auto& m : d.sequences()) {
    EXPECT_FALSE(m.category.empty());
    const PressureSequence s = d.read(m.name);
    for (int t = 0; t < s.frames(); ++t)
      for (int i = 0; i < s.mat.cells(); ++i) {
        if (gain[i] == 0) EXPECT_EQ(s.frame(t)[i], 0.0f);
        total += s.frame(t)[i];
      }
  }
  EXPECT_GT(total, 0.0);  // the subjects do press on the mat
  std::filesystem::remove(path);
}
TEST(HarStandin, MocapClipsAreGroupedByCmuSubjectOnTheirOwnBodies) {
  namespace fs = std::filesystem;
  if (!fs::exists(fs::path(PTNET_SHARED_MOCAP) / "clips.csv")) GTEST_SKIP() << "../shared/mocap not found";
  const auto clips = ptnet::read_clips_csv(std::string(PTNET_SHARED_MOCAP) + "/clips.csv");
  ASSERT_EQ(clips.size(), 11u);
  std::map<std::string, std::set<std::string>> expected;  // subject -> categories, from clips.csv
  for (const auto& c : clips) expected["s" + c.subject].insert(c.category);

  const std::string path = (fs::temp_directory_path() / ("ptnet_har_standin_mocap_test_" + std::to_string(::getpid()) + ".h5")).string();
  StandinOptions o;
  o.mocap = PTNET_SHARED_MOCAP;
  o.threads = 1;
  write_standin(path, o, /*force=*/true);
  const Dataset d = Dataset::open(path);
  // One subject per CMU subject, numeric order, each its own body.
  std::vector<std::string> ids;
  std::set<double> heights;
  for (const auto& b : d.bodies()) {
    ids.push_back(b.id);
    heights.insert(b.height_cm);
    EXPECT_EQ(b.role, "original");
    EXPECT_GE(b.height_cm, 150);
    EXPECT_LE(b.height_cm, 200);
  }
  EXPECT_EQ(ids, (std::vector<std::string>{"s2", "s5", "s6", "s14", "s141"}));
  EXPECT_EQ(heights.size(), 5u);
  EXPECT_EQ(d.bodies()[0].sex, Sex::female);
  EXPECT_EQ(d.bodies()[1].sex, Sex::male);
  EXPECT_NE(d.info().config_json.find("stand-in"), std::string::npos);
  EXPECT_NE(d.info().config_json.find("mocap"), std::string::npos);

  // Every clip once, on its own subject's body, with its category.
  ASSERT_EQ(d.sequences().size(), 11u);
  std::map<std::string, std::set<std::string>> found;
  const auto gain = standin_gain_map(d.info().mat, o);
  for (const auto& m : d.sequences()) {
    EXPECT_EQ(m.body_id, "s" + m.performer.substr(3)) << m.name;  // performer "CMU<n>"
    found[m.body_id].insert(m.category);
    const PressureSequence s = d.read(m.name);
    double total = 0;
    for (int t = 0; t < s.frames(); ++t)
      for (int i = 0; i < s.mat.cells(); ++i) {
        if (gain[i] == 0) ASSERT_EQ(s.frame(t)[i], 0.0f);
        total += s.frame(t)[i];
      }
    EXPECT_GT(total, 0.0) << m.name;  // the subject does press on the mat
  }
  EXPECT_EQ(found, expected);
  // 14_06: 1440 motion frames at 120 Hz after the T-pose = 12 s -> 360 frames at 30 Hz.
  EXPECT_NEAR(d.sequence("standin_14_06__s14").frames, 360, 1);
  EXPECT_EQ(d.sequence("standin_14_06__s14").category, "rom");
  fs::remove(path);
}

// The real-motion stand-in of docs/har.md: every clip of the 44-clip corpus
// (../shared/mocap-corpus, 7 CMU performers) on its performer's own body.
TEST(HarStandin, CorpusStandinHasOneSubjectPerCmuPerformerWithItsCategories) {
  namespace fs = std::filesystem;
  const fs::path corpus = PTNET_SHARED_CORPUS;
  if (!fs::exists(corpus / "clips.csv"))
    GTEST_SKIP() << corpus.string() << "/clips.csv not found: the real-motion corpus is not beside the source tree";
  std::map<std::string, std::set<std::string>> expected;  // subject -> categories, from clips.csv
  std::map<std::string, int> clips_of;
  for (const auto& c : ptnet::read_clips_csv((corpus / "clips.csv").string())) {
    expected["s" + c.subject].insert(c.category);
    ++clips_of["s" + c.subject];
  }
  const std::string path = (fs::temp_directory_path() / ("ptnet_har_standin_corpus_test_" + std::to_string(::getpid()) + ".h5")).string();
  StandinOptions o;
  o.mocap = corpus.string();
  o.placement = "follow";  // as documented: the real clips leave a fixed 1.6 m mat
  o.threads = 1;
  write_standin(path, o, /*force=*/true);
  const Dataset d = Dataset::open(path);
  EXPECT_NE(d.info().config_json.find("\"placement\":\"follow\""), std::string::npos);
  std::vector<std::string> ids;
  for (const auto& b : d.bodies()) ids.push_back(b.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"s1", "s2", "s3", "s5", "s6", "s14", "s141"}));
  std::map<std::string, std::set<std::string>> found;
  std::map<std::string, int> sequences_of;
  long long frames = 0, loaded = 0;  // frames carrying at least 100 N
  for (const auto& m : d.sequences()) {
    EXPECT_EQ(m.body_id, "s" + m.performer.substr(3)) << m.name;  // performer "CMU<n>"
    EXPECT_GE(m.frames, 30) << m.name;  // every clip gives at least one HAR window
    found[m.body_id].insert(m.category);
    ++sequences_of[m.body_id];
    const PressureSequence s = d.read(m.name);
    for (int t = 0; t < s.frames(); ++t) {
      double kpa = 0;
      for (int i = 0; i < s.mat.cells(); ++i) kpa += s.frame(t)[i];
      loaded += kpa * 1000 * s.mat.cell_area_m2() >= 100;
      ++frames;
    }
  }
  // The mat follows the body: the activity is on it (measured 89 %; the
  // rest are flight phases of jumps and leaps, and the run/jog and
  // uneven-terrain clips). A fixed mat senses 63 %.
  EXPECT_GT(double(loaded) / double(frames), 0.8);
  EXPECT_EQ(found, expected);
  EXPECT_EQ(sequences_of, clips_of);
  // The documented split (train 2,3,5,14 / test 1,6,141) has every category
  // performed by two or more performers on both sides; freestyle (s5 only)
  // can only train.
  const std::set<std::string> train = {"s2", "s3", "s5", "s14"}, test = {"s1", "s6", "s141"};
  std::map<std::string, std::set<std::string>> sides;  // category -> "train" / "test"
  std::map<std::string, int> performers;
  for (const auto& [subject, categories] : found)
    for (const auto& c : categories) {
      sides[c].insert(train.count(subject) ? "train" : test.count(subject) ? "test" : "none");
      ++performers[c];
    }
  for (const auto& [c, n] : performers)
    EXPECT_EQ(sides[c], (n >= 2 ? std::set<std::string>{"test", "train"} : std::set<std::string>{"train"})) << c;
  EXPECT_EQ(performers["freestyle"], 1);
  fs::remove(path);
}

TEST(HarStandin, BadClipsCsvLinesNameFileAndLine) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("ptnet_har_standin_bad_clips_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string csv = (dir / "clips.csv").string();
  auto message = [&](const std::string& text) {
    std::ofstream(csv) << text;
    try {
      ptnet::read_clips_csv(csv);
    } catch (const ptnet::Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("file,subject,category,take\na.bvh,2,dancing,1\n"),
            csv + ":2: expected category walking, rom, freestyle or acting, found 'dancing'");
  EXPECT_EQ(message("file,subject,category,take\na.bvh,2,rom\n"),
            csv + ":2: expected 4 fields (as the header), found 3");
  EXPECT_EQ(message("file,subject,take\na.bvh,2,1\n"),
            csv + ":1: expected a header with column category (file,subject,category,take[,metres_per_unit,up,marker_map,static]), "
                  "found 'file,subject,take'");
  EXPECT_EQ(message("file,subject,category,take\na.bvh,2,rom,0\n"),
            csv + ":2: expected take as an integer in 1-1000000, found '0'");
  fs::remove_all(dir);
}
