// The validate-har experiment end to end on a tiny hand-made dataset: two
// activities (a block sliding along the mat vs two feet rocking in place)
// that mean shift must separate and the classifiers must learn; bad subject
// lists give one-line errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "har/har_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

using namespace ptnet;
using namespace ptnet::har;

namespace {

constexpr int kFrames = 120;

// [T, 20, 12] kPa: "walking" = a 3x3 block sliding along the mat and back;
// "rom" = two 3x2 feet in place whose load rocks left/right.
PressureSequence make(const std::string& category, int subject, std::uint64_t seed) {
  PressureSequence s(MatSpec{20, 12, 0.02}, kFrames, 30);
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0, 0.3f);
  const float load = 20.0f + 3.0f * subject;
  for (int t = 0; t < kFrames; ++t) {
    if (category == "walking") {
      const int phase = t % 34, r0 = phase < 17 ? phase : 33 - phase;
      for (int r = r0; r < r0 + 3; ++r)
        for (int c = 4; c < 7; ++c) s.at(t, r, c) = load;
    } else {
      const double w = 0.5 + 0.4 * std::sin(t * 0.3);
      for (int r = 8; r < 11; ++r)
        for (int c = 2; c < 4; ++c) {
          s.at(t, r, c) = float(load * w);
          s.at(t, r, c + 6) = float(load * (1 - w));
        }
    }
    for (int i = 0; i < s.mat.cells(); ++i) s.frame(t)[i] = std::max(0.0f, s.frame(t)[i] + noise(rng));
  }
  return s;
}

// One file per test (CTest runs tests in parallel).
std::string write_dataset(const std::string& name) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("ptnet_har_" + name + "_" + std::to_string(::getpid()) + ".h5")).string();
  DatasetInfo info;
  info.mat = MatSpec{20, 12, 0.02};
  info.generator = "har_experiment_test";
  std::vector<BodySpec> bodies;
  for (int s = 1; s <= 4; ++s)
    bodies.push_back(BodySpec{"s" + std::to_string(s), s % 2 ? Sex::female : Sex::male,
                              160.0 + 5 * s, 60.0 + 4 * s, "original"});
  DatasetWriter w(path, info, bodies, /*force=*/true);
  for (int s = 1; s <= 4; ++s)
    for (const std::string cat : {"walking", "rom"}) {
      SequenceMeta m;
      m.motion_id = cat + "_p" + std::to_string(s);
      m.body_id = "s" + std::to_string(s);
      m.name = m.motion_id + "__" + m.body_id;
      m.performer = "P" + std::to_string(s);
      m.category = cat;
      m.take = 1;
      m.source = "test";
      w.add(m, make(cat, s, 100 * s + (cat == "rom")));
    }
  w.commit();
  return path;
}

// The "model": scales pressure by the weight ratio.
PressureSequence scale_by_weight(const PressureSequence& s, const BodySpec& from, const BodySpec& to) {
  PressureSequence out = s;
  for (float& v : out.kpa) v *= float(to.weight_kg / from.weight_kg);
  return out;
}

HarOptions small_options() {
  HarOptions o;
  o.train_subjects = {"1", "2"};
  o.test_subjects = {"3", "4"};
  o.runs = 2;
  o.stride = 5;
  o.synthetic_bodies = 2;
  o.input.pool = 2;
  o.classifier.epochs = 6;
  return o;
}

}  // namespace

TEST(HarExperiment, TwoActivitiesAreFoundAndLearnedFromEverySource) {
  const Dataset d = Dataset::open(write_dataset("two_activities"));
  const HarResult r = validate_har(d, scale_by_weight, small_options());
  EXPECT_EQ(r.train_subjects, (std::vector<std::string>{"s1", "s2"}));
  EXPECT_EQ(r.test_subjects, (std::vector<std::string>{"s3", "s4"}));
  // 2 subjects x 2 clips x 19 windows (starts 0, 5, ..., 90).
  EXPECT_EQ(r.train_windows, 2 * 2 * 19);
  EXPECT_EQ(r.test_windows, 2 * 2 * 19);
  ASSERT_EQ(r.clusters, 2);
  EXPECT_DOUBLE_EQ(r.cluster_purity, 1.0);  // clusters = the two activities
  ASSERT_EQ(r.sources.size(), 3u);
  EXPECT_EQ(r.sources[1].train_windows, 2 * r.train_windows);  // 2 synthetic bodies
  EXPECT_EQ(r.sources[2].train_windows, 3 * r.train_windows);
  for (const auto& s : r.sources) {
    EXPECT_EQ(s.macro_f1.size(), 2u);
    EXPECT_GE(s.macro_f1_mean, 0.9) << s.source;
    EXPECT_GE(s.category_macro_f1_mean, 0.9) << s.source;
    EXPECT_EQ(s.confusion.sum(), 2 * r.test_windows);  // summed over 2 runs
  }
  EXPECT_NE(format_table(r).find("Macro F1 score (pseudo labels)"), std::string::npos);
  EXPECT_NE(to_json(r).find("\"real+synthetic\""), std::string::npos);

  // The figure: a PNG, refused without force once it exists.
  const std::string png =
      (std::filesystem::temp_directory_path() / ("ptnet_har_two_activities_" + std::to_string(::getpid()) + ".png")).string();
  write_confusion_png(png, r, /*force=*/true);
  std::ifstream f(png, std::ios::binary);
  char magic[8] = {};
  f.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  EXPECT_THROW(write_confusion_png(png, r, /*force=*/false), Error);
}

TEST(HarExperiment, BadSubjectListsAreOneLineErrors) {
  const std::string path = write_dataset("bad_subjects");
  const Dataset d = Dataset::open(path);
  HarOptions o = small_options();
  o.test_subjects = {"2", "3"};
  try {
    validate_har(d, scale_by_weight, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": subject s2 is in both the training and the test subjects");
  }
  o.test_subjects = {"9"};
  try {
    validate_har(d, scale_by_weight, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path + ": no subject '9' (bodies: s1,s2,s3,s4)");
  }
  o.test_subjects = {};
  EXPECT_THROW(validate_har(d, scale_by_weight, o), Error);
}

TEST(HarExperiment, PaperBodiesAreSeededAndPlausible) {
  const auto a = sample_paper_bodies(20, 3), b = sample_paper_bodies(20, 3);
  ASSERT_EQ(a.size(), 20u);
  double male_h = 0, female_h = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].height_cm, b[i].height_cm);
    EXPECT_EQ(a[i].weight_kg, b[i].weight_kg);
    (a[i].sex == Sex::male ? male_h : female_h) += a[i].height_cm / 10;
  }
  EXPECT_NEAR(male_h, 175, 12);    // mean of 10 draws of N(175, 15)
  EXPECT_NEAR(female_h, 165, 12);
}
