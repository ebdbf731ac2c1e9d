// ptnet/body_spec.hpp: the three attributes that define a body, and a bodies
// table as read from / written to CSV (`id,sex,height_cm,weight_kg[,role]`).
//
//   auto bodies = ptnet::read_bodies_csv("bodies.csv");   // validated
//   ptnet::validate(BodySpec{"b1", Sex::female, 165, 60});  // throws if impossible
#pragma once

#include <string>
#include <vector>

namespace ptnet {

enum class Sex { female = 0, male = 1 };

inline constexpr double kMinHeightCm = 100, kMaxHeightCm = 230;
inline constexpr double kMinWeightKg = 20, kMaxWeightKg = 250;

struct BodySpec {
  std::string id;
  Sex sex = Sex::female;
  double height_cm = 165;
  double weight_kg = 65;
  std::string role = "retargeted";  // "retargeted" (training) or "original" (held out)
};

// "female"/"male" (also "f"/"m", "0"/"1"); throws Error otherwise.
Sex parse_sex(const std::string& text);
const char* sex_name(Sex sex);

// Throws Error ("body b3: height_cm 260 outside 100-230") for impossible values.
void validate(const BodySpec& body);

// Parses "female,165,60" (the --source/--target form of the CLI).
BodySpec parse_body_attributes(const std::string& text);

std::vector<BodySpec> read_bodies_csv(const std::string& path);
// The same on CSV text (`source` names it in messages).
std::vector<BodySpec> parse_bodies_csv(const std::string& text, const std::string& source);
std::string format_bodies_csv(const std::vector<BodySpec>& bodies);

}  // namespace ptnet
