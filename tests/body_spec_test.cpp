// Body attributes and the bodies CSV (issue 3).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>

#include "ptnet/body.hpp"
#include "ptnet/error.hpp"

namespace ptnet {
namespace {

TEST(BodySpec, SampledBodiesRoundTripThroughCsv) {
  const auto bodies = sample_bodies(8, 8, 2, 2, 5);
  ASSERT_EQ(bodies.size(), 20u);
  int originals = 0;
  for (const auto& b : bodies) {
    EXPECT_NO_THROW(validate(b));
    originals += b.role == "original";
  }
  EXPECT_EQ(originals, 4);
  const auto path = (std::filesystem::temp_directory_path() /
                     ("ptnet_bodies_" + std::to_string(::getpid()) + ".csv")).string();
  { std::ofstream(path) << format_bodies_csv(bodies); }
  const auto back = read_bodies_csv(path);
  std::filesystem::remove(path);
  ASSERT_EQ(back.size(), bodies.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].id, bodies[i].id);
    EXPECT_EQ(back[i].sex, bodies[i].sex);
    EXPECT_DOUBLE_EQ(back[i].height_cm, bodies[i].height_cm);
    EXPECT_DOUBLE_EQ(back[i].weight_kg, bodies[i].weight_kg);
    EXPECT_EQ(back[i].role, bodies[i].role);
  }
  // Adding originals never changes the retargeted bodies (independent streams).
  const auto fewer = sample_bodies(8, 8, 0, 0, 5);
  for (std::size_t i = 0; i < fewer.size(); ++i) EXPECT_DOUBLE_EQ(fewer[i].height_cm, bodies[i].height_cm);
}

TEST(BodySpec, ImpossibleAttributesAreErrors) {
  EXPECT_THROW(validate(BodySpec{"b", Sex::male, 260, 70}), Error);
  EXPECT_THROW(validate(BodySpec{"b", Sex::male, 175, 10}), Error);
  EXPECT_THROW(parse_sex("other"), Error);
  const BodySpec b = parse_body_attributes("female,165,60");
  EXPECT_EQ(b.sex, Sex::female);
  EXPECT_DOUBLE_EQ(b.height_cm, 165);
  EXPECT_THROW(parse_body_attributes("female,165"), Error);
}

TEST(BodySpec, OneParserForEveryCaseOfTheSexWord) {
  for (const char* text : {"Male,185,95", "MALE,185,95", " m , 185 , 95", "1,185,95"}) {
    const BodySpec b = parse_body_attributes(text, "--target");
    EXPECT_EQ(b.sex, Sex::male) << text;
    EXPECT_DOUBLE_EQ(b.height_cm, 185) << text;
    EXPECT_DOUBLE_EQ(b.weight_kg, 95) << text;
  }
  EXPECT_EQ(parse_body_attributes("Female,160,55").sex, Sex::female);
  for (const char* bad : {"giant,300", "male,185", "male,185,95,1", "male,1.8m,95", "male,,95"}) {
    try {
      parse_body_attributes(bad, "--target");
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("--target: expected SEX,HEIGHT_CM,WEIGHT_KG like female,165,60, found '") + bad + "'");
    }
  }
  // The range is the one validator's, in every place that checks it.
  EXPECT_EQ(body_range_problem(BodySpec{"b", Sex::male, 300, 80}), "height_cm 300 outside 100-230");
  EXPECT_EQ(body_range_problem(BodySpec{"b", Sex::male, 180, 5}), "weight_kg 5 outside 20-250");
  EXPECT_EQ(body_range_problem(BodySpec{"b", Sex::male, 180, 80}), "");
}

TEST(BodySpec, PaperBodiesComeFromTheProjectsOwnGaussian) {
  // Box-Muller on raw 53-bit uniforms: these numbers hold with every standard library.
  std::mt19937_64 rng(7);
  const BodySpec b = draw_paper_body(rng, Sex::male, "m", "retargeted");
  std::mt19937_64 again(7);
  const double h = 175 + 15 * standard_normal(again);
  const double w = 75 + 10 * standard_normal(again);
  EXPECT_DOUBLE_EQ(b.height_cm, std::round(h * 10) / 10);
  EXPECT_DOUBLE_EQ(b.weight_kg, std::round(w * 10) / 10);
}

TEST(BodySpec, HeavierBodyAtTheSameHeightIsThicker) {
  const Body light(BodySpec{"a", Sex::female, 165, 50});
  const Body heavy(BodySpec{"b", Sex::female, 165, 90});
  EXPECT_GT(heavy.segments()[0].radius_a_m, light.segments()[0].radius_a_m);
}

}  // namespace
}  // namespace ptnet
