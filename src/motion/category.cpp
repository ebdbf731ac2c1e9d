// Motion categories and procedural performers.
#include <algorithm>
#include <cmath>

#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "rig.hpp"

namespace ptnet {

Category parse_category(const std::string& text) {
  for (Category c : kCategories)
    if (text == category_name(c)) return c;
  throw Error("expected a category (walking, rom, freestyle, acting), found '" + text + "'");
}

const char* category_name(Category category) {
  switch (category) {
    case Category::walking: return "walking";
    case Category::rom: return "rom";
    case Category::freestyle: return "freestyle";
    case Category::acting: return "acting";
  }
  return "?";
}

std::string motion_id(int performer, Category category, int take) {
  return "p" + std::to_string(performer) + "_" + category_name(category) + "_t" + std::to_string(take);
}

int performer_sex(int performer, std::uint64_t seed) {
  return int((std::uint64_t(performer) + seed) % 2);  // alternating, so any set is balanced
}

// Adult stature, normal by sex, clamped to 150-200 cm: means 163 cm (female)
// and 177 cm (male), SD ~7 cm (NCD-RisC 2016 adult height, high-income
// countries).
double performer_height_cm(int performer, std::uint64_t seed) {
  const int sex = performer_sex(performer, seed);
  rig::Rng rng(seed, 0x5065726654ULL, std::uint64_t(performer));
  const double h = sex == 1 ? rng.normal(177.0, 7.0) : rng.normal(163.0, 6.5);
  return std::round(std::clamp(h, 150.0, 200.0) * 10) / 10;
}

}  // namespace ptnet
