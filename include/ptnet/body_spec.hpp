// ptnet/body_spec.hpp: the three attributes that define a body, and a bodies
// table as read from / written to CSV (`id,sex,height_cm,weight_kg[,role]`).
// The one parser, validator and sampler of body attributes (core layer).
//
//   auto bodies = ptnet::read_bodies_csv("bodies.csv");        // validated
//   ptnet::validate(BodySpec{"b1", Sex::female, 165, 60});     // throws if impossible
//   BodySpec t = ptnet::parse_body_attributes("Male,185,95");  // the CLI's --target
//   ptnet::check_body_range(t, "target body");  // "target body: height_cm 300 outside 100-230"
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "ptnet/paper.hpp"

namespace ptnet {

enum class Sex { female = 0, male = 1 };

struct BodySpec {
  std::string id;
  Sex sex = Sex::female;
  double height_cm = 165;
  double weight_kg = 65;
  std::string role = "retargeted";  // "retargeted" (training) or "original" (held out)
};

// "female"/"male" (also "f"/"m", "0"/"1"), any case; throws Error otherwise.
Sex parse_sex(const std::string& text);
const char* sex_name(Sex sex);

// What is impossible about a body's sex, height or weight
// ("height_cm 260 outside 100-230"), or "" when they are in range.
std::string body_range_problem(const BodySpec& body);
// Throws Error "WHAT: height_cm 300 outside 100-230" for an impossible body.
void check_body_range(const BodySpec& body, const std::string& what);
// The same and the role; throws Error ("body b3: height_cm 260 outside 100-230").
void validate(const BodySpec& body);

// Parses "female,165,60" (the --source/--target form of the CLI; sex in any
// case) into a body with id `what`; the values are not range-checked (that is
// check_body_range, with the caller's name for the body). Errors name `what`:
// "--target: expected SEX,HEIGHT_CM,WEIGHT_KG like female,165,60, found 'giant,300'".
BodySpec parse_body_attributes(const std::string& text, const std::string& what = "body attributes");

// One body of a table row (bodies CSV, recordings manifest), checked:
// errors "FILE:LINE: expected height_cm in 100-230, found 260".
BodySpec parse_body_fields(const std::string& file, long line, const std::string& id, const std::string& sex,
                           const std::string& height_cm, const std::string& weight_kg);

std::vector<BodySpec> read_bodies_csv(const std::string& path);
std::string format_bodies_csv(const std::vector<BodySpec>& bodies);

// The body `height_sd` and `weight_sd` standard deviations from the mean of
// the paper's distribution for `sex` (paper.hpp), clamped to the accepted
// range, rounded to 0.1.
BodySpec paper_body_at(Sex sex, double height_sd, double weight_sd, const std::string& id, const std::string& role);
// A body drawn from that distribution: height then weight from `rng`.
BodySpec draw_paper_body(std::mt19937_64& rng, Sex sex, const std::string& id, const std::string& role);
// `count` points of a Latin hypercube over [0, 1)^2: point i sits at the
// centres of strata a[i] and b[i] of `count` each, a and b two permutations
// of 0..count-1 drawn from `rng` (Fisher-Yates on the raw generator: the
// same points with every standard library). Each stratum of both axes is
// used once: `count` points cover both ranges evenly.
std::vector<std::array<double, 2>> latin_hypercube(int count, std::mt19937_64& rng);

}  // namespace ptnet
