// ptnet/body.hpp: a human body from (sex, height, weight), posed on the
// canonical skeleton, as the pressure simulator sees it.
//
//   ptnet::Body body(ptnet::BodySpec{"b1", ptnet::Sex::female, 165, 60});
//   ptnet::PosedBody posed = ptnet::pose_body(body, pose);   // world geometry
//   Eigen::Vector3d com = ptnet::centre_of_mass(body, pose);  // m
//
//   auto bodies = ptnet::sample_bodies(8, 8, 2, 2, /*seed=*/1);  // the paper's 16 + 4
//
// Model (docs/anthropometry.md):
//  - segment lengths come from the pose (the canonical skeleton scaled by
//    height, Drillis & Contini 1966); segment masses are sex-specific fractions
//    of body weight (de Leva 1996), normalised to sum exactly to the weight;
//  - every segment is a tapered capsule between canonical joints whose radius
//    is solved from its mass and the tissue density (1050 kg/m^3), so weight
//    at a fixed height thickens the body;
//  - each foot carries a plantar sole surface (heel pad, lateral midfoot band,
//    raised medial arch, metatarsal heads, toes) of length 0.152 H and width
//    0.055 H (widened with body-mass index), given as a height table over the
//    sole plane in two rigid patches: hindfoot (heel to the metatarsal heads)
//    and toes (hinged at the metatarsophalangeal joint).
//
// Dimension legend: K = kJointCount canonical joints, S segments (kSegmentCount).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {

// Segments of the body (both sides of each limb).
enum Segment : int {
  kSegHeadNeck, kSegUpperTrunk, kSegMiddleTrunk, kSegLowerTrunk,
  kSegLeftUpperArm, kSegLeftForearm, kSegLeftHand,
  kSegRightUpperArm, kSegRightForearm, kSegRightHand,
  kSegLeftThigh, kSegLeftShank, kSegLeftFoot,
  kSegRightThigh, kSegRightShank, kSegRightFoot,
  kSegmentCount
};

// How a segment's end points follow the pose. The proximal end is
// pose[joint_a]; the distal end is pose[joint_b], moved on by extension_m
// along pose[joint_b] - pose[dir_from] when extension_m > 0 (head top, hand).
struct SegmentShape {
  int joint_a = 0, joint_b = 0, dir_from = 0;
  double extension_m = 0;
  double mass_kg = 0;
  double radius_a_m = 0, radius_b_m = 0;  // capsule radius at each end (m)
  bool touches_ground = true;  // false for the feet: their soles do instead
};

// The plantar sole of one foot: a height table over normalised sole
// coordinates u (0 at the back of the heel, 1 at the toe tip, along the foot)
// and v (across the foot, in units of the foot width, positive towards the
// medial side). Heights are metres above the sole plane; +inf outside the
// foot outline. Left and right share the table (mirrored through v).
struct SoleSurface {
  double length_m = 0;       // heel back to toe tip, 0.152 H
  double width_m = 0;        // at the metatarsal heads, 0.055 H x BMI factor
  double ankle_height_m = 0; // ankle joint centre above the sole plane, 0.039 H
  double ankle_u = 0.22;     // the ankle lies above this u
  double mtp_u = 0.74;       // the toes hinge here
  double arch_height_m = 0;  // peak rise of the medial arch
  int nu = 0, nv = 0;        // table size
  double v_min = -0.6, v_max = 0.6;  // table extent in v
  std::vector<float> height_m;  // [nu, nv], m above the sole plane (+inf: not foot)

  // Height (m) above the sole plane at (u, v), +inf outside the foot.
  float at(double u, double v) const {
    int i = int(u * (nu - 1) + 0.5), j = int((v - v_min) / (v_max - v_min) * (nv - 1) + 0.5);
    if (u < 0 || i >= nu || j < 0 || j >= nv) return kOutside;
    return height_m[std::size_t(i) * nv + j];
  }
  static constexpr float kOutside = 1e30f;
};

class Body {
 public:
  explicit Body(const BodySpec& spec);  // validates; throws Error

  const BodySpec& spec() const { return spec_; }
  double height_m() const { return spec_.height_cm / 100.0; }
  double mass_kg() const { return spec_.weight_kg; }
  double bmi() const;  // kg/m^2
  const std::array<SegmentShape, kSegmentCount>& segments() const { return segments_; }
  const SoleSurface& sole() const { return sole_; }

 private:
  BodySpec spec_;
  std::array<SegmentShape, kSegmentCount> segments_{};
  SoleSurface sole_;
};

// A posed rigid patch of a sole: the plane through `origin` (the sole point
// under the ankle, or under the toe joint for the toes) spanned by `forward`
// and `left` (the body's left, for both feet) with normal `up`; the patch
// covers u in [u_begin, u_end] and the sole point at origin has u = u_origin.
struct SolePatch {
  Eigen::Vector3d origin, forward, left, up;
  double u_origin = 0, u_begin = 0, u_end = 1;
  double medial_sign = 1;  // v = medial_sign * (left offset) / width
};

// World geometry of a posed body. Capsule end points a, b (m) per segment,
// two sole patches per foot (hindfoot, toes).
struct PosedBody {
  std::array<Eigen::Vector3d, kSegmentCount> a, b;
  std::array<SolePatch, 2> left_foot, right_foot;  // [hindfoot, toes]
};

// World geometry of `body` in `pose` (canonical joints, world, m).
PosedBody pose_body(const Body& body, const Pose& pose);

// Whole-body centre of mass (m): segment masses at their capsule midpoints.
Eigen::Vector3d centre_of_mass(const Body& body, const Pose& pose);

// How the retargeted bodies of sample_bodies are drawn from each sex's
// distribution of the paper (stature and weight independent):
//   paper  Gaussian draws, as in the paper;
//   cover  a Latin hypercube over mean +- kCoverSd sd of stature and of
//          weight, so that a few bodies reach the tails evenly (16 bodies:
//          132-208 cm, 43-97 kg) where Gaussian draws leave gaps.
enum class BodySampling { paper, cover };
inline constexpr double kCoverSd = 2.5;
BodySampling parse_body_sampling(const std::string& name);  // "paper" | "cover"

// Bodies sampled as in the paper: `males` (175 +- 15 cm, 75 +- 10 kg) and
// `females` (165 +- 15 cm, 65 +- 10 kg) retargeted bodies, drawn as
// `sampling` says, clipped to the valid ranges, rounded to 0.1 cm / 0.1 kg;
// plus held-out "original" bodies (originals_f female, originals_m male),
// Gaussian draws from an independent random stream, so adding originals
// never changes the retargeted bodies (nor the sampling the originals).
// Ids: f01.., m01.. (retargeted), of01.., om01.. (original). Each count in
// kBodyCountRange (an Error naming it otherwise), not all 0.
inline constexpr Range kBodyCountRange{0, 10000};
std::vector<BodySpec> sample_bodies(int males, int females, int originals_f, int originals_m,
                                    std::uint64_t seed, BodySampling sampling = BodySampling::paper);

}  // namespace ptnet
