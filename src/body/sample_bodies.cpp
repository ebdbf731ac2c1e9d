// Body sets sampled as in the paper (PressureTransferNet, Sec. 3; the
// distribution: ptnet/paper.hpp, the draw: draw_paper_body).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "ptnet/body.hpp"
#include "ptnet/error.hpp"

namespace ptnet {
namespace {

std::string numbered(const char* prefix, int i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s%02d", prefix, i);
  return buf;
}

// `count` bodies of `sex` on a Latin hypercube over mean +- kCoverSd sd.
void cover_bodies(std::vector<BodySpec>& out, std::mt19937_64& rng, Sex sex, int count, const char* prefix) {
  const std::vector<std::array<double, 2>> points = latin_hypercube(count, rng);
  for (int i = 0; i < count; ++i)
    out.push_back(paper_body_at(sex, (2 * points[std::size_t(i)][0] - 1) * kCoverSd,
                                (2 * points[std::size_t(i)][1] - 1) * kCoverSd, numbered(prefix, i + 1), "retargeted"));
}

}  // namespace

BodySampling parse_body_sampling(const std::string& name) {
  if (name == "paper") return BodySampling::paper;
  if (name == "cover") return BodySampling::cover;
  throw Error("body sampling: expected paper or cover, found '" + name + "'");
}

std::vector<BodySpec> sample_bodies(int males, int females, int originals_f, int originals_m,
                                    std::uint64_t seed, BodySampling sampling) {
  check_range("males", males, kBodyCountRange);
  check_range("females", females, kBodyCountRange);
  check_range("originals_f", originals_f, kBodyCountRange);
  check_range("originals_m", originals_m, kBodyCountRange);
  if (males + females + originals_f + originals_m == 0) throw Error("sample_bodies: no bodies requested");
  // Four independent streams, so that e.g. adding originals or males never
  // changes the other bodies.
  std::mt19937_64 rf(seed * 4 + 0x9e3779b97f4a7c15ULL), rm(seed * 4 + 1 + 0x9e3779b97f4a7c15ULL);
  std::mt19937_64 of(seed * 4 + 2 + 0x9e3779b97f4a7c15ULL), om(seed * 4 + 3 + 0x9e3779b97f4a7c15ULL);
  std::vector<BodySpec> out;
  if (sampling == BodySampling::cover) {
    cover_bodies(out, rf, Sex::female, females, "f");
    cover_bodies(out, rm, Sex::male, males, "m");
  } else {
    for (int i = 1; i <= females; ++i) out.push_back(draw_paper_body(rf, Sex::female, numbered("f", i), "retargeted"));
    for (int i = 1; i <= males; ++i) out.push_back(draw_paper_body(rm, Sex::male, numbered("m", i), "retargeted"));
  }
  for (int i = 1; i <= originals_f; ++i) out.push_back(draw_paper_body(of, Sex::female, numbered("of", i), "original"));
  for (int i = 1; i <= originals_m; ++i) out.push_back(draw_paper_body(om, Sex::male, numbered("om", i), "original"));
  return out;
}

}  // namespace ptnet
