// Body sets sampled as in the paper (PressureTransferNet, Sec. 3: male
// 175 +- 15 cm, 75 +- 10 kg; female 165 +- 15 cm, 65 +- 10 kg, Gaussian).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "ptnet/body.hpp"
#include "ptnet/error.hpp"

namespace ptnet {
namespace {

// Standard normal by Box-Muller on raw 53-bit uniforms: the same numbers on
// every platform (std::normal_distribution is implementation-defined).
double gaussian(std::mt19937_64& rng) {
  auto uniform = [&] { return (double(rng() >> 11) + 0.5) * (1.0 / 9007199254740992.0); };
  double u1 = uniform(), u2 = uniform();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

double round1(double v) { return std::round(v * 10) / 10; }

BodySpec draw(std::mt19937_64& rng, Sex sex, const std::string& id, const char* role) {
  const bool male = sex == Sex::male;
  BodySpec b;
  b.id = id;
  b.sex = sex;
  b.height_cm = round1(std::clamp((male ? 175.0 : 165.0) + 15.0 * gaussian(rng), kMinHeightCm, kMaxHeightCm));
  b.weight_kg = round1(std::clamp((male ? 75.0 : 65.0) + 10.0 * gaussian(rng), kMinWeightKg, kMaxWeightKg));
  b.role = role;
  return b;
}

std::string numbered(const char* prefix, int i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s%02d", prefix, i);
  return buf;
}

}  // namespace

std::vector<BodySpec> sample_bodies(int males, int females, int originals_f, int originals_m,
                                    std::uint64_t seed) {
  if (males < 0 || females < 0 || originals_f < 0 || originals_m < 0)
    throw Error("sample_bodies: counts must be >= 0");
  if (males + females + originals_f + originals_m == 0) throw Error("sample_bodies: no bodies requested");
  // Four independent streams, so that e.g. adding originals or males never
  // changes the other bodies.
  std::mt19937_64 rf(seed * 4 + 0x9e3779b97f4a7c15ULL), rm(seed * 4 + 1 + 0x9e3779b97f4a7c15ULL);
  std::mt19937_64 of(seed * 4 + 2 + 0x9e3779b97f4a7c15ULL), om(seed * 4 + 3 + 0x9e3779b97f4a7c15ULL);
  std::vector<BodySpec> out;
  for (int i = 1; i <= females; ++i) out.push_back(draw(rf, Sex::female, numbered("f", i), "retargeted"));
  for (int i = 1; i <= males; ++i) out.push_back(draw(rm, Sex::male, numbered("m", i), "retargeted"));
  for (int i = 1; i <= originals_f; ++i) out.push_back(draw(of, Sex::female, numbered("of", i), "original"));
  for (int i = 1; i <= originals_m; ++i) out.push_back(draw(om, Sex::male, numbered("om", i), "original"));
  return out;
}

}  // namespace ptnet
