// Canonical skeleton: rest bone offsets from anthropometric proportions.
//
// Source: Drillis & Contini (1966) segment fractions of standing height H, as
// reproduced in Winter, Biomechanics and Motor Control of Human Movement,
// Fig. 4.1 (src/core/anthropometry.hpp, docs/anthropometry.md).
// The layout is the one the motion, body and sim stages agree on
// (ptnet-team notes, "The canonical skeleton").
#include "core/anthropometry.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "rig.hpp"

#include <cmath>
#include <string>

namespace ptnet {

namespace {
const auto& kLen = anthropometry::kDrillisContini;
}  // namespace

Pose canonical_rest_offsets(double height_cm) {
  if (!(height_cm > 0) || !std::isfinite(height_cm))
    throw Error("canonical_rest_offsets: expected a positive height in cm, found " +
                std::to_string(height_cm));
  const double h = height_cm / 100.0;
  // Hip joint centres ~half the hip (trochanter) width apart: 0.191 H / 4,
  // 0.0475 H each side as in the team skeleton.
  const double hip_half = 0.0475;
  const double shoulder_half = 0.5 * kLen.shoulder_width;  // acromion at the shoulder breadth
  const double spine = 0.070;                              // pelvis -> lumbar (0.600 H)
  const double chest = kLen.chest - kLen.hip - spine;      // -> 0.720 H (nipple)
  const double neck = kLen.shoulder - kLen.chest;          // -> 0.818 H (acromion)
  const double head = kLen.chin - kLen.shoulder;           // -> 0.870 H (chin)
  Pose o;
  o[kPelvis] = {0, 0, kLen.hip * h};
  o[kSpine] = {0, 0, spine * h};
  o[kChest] = {0, 0, chest * h};
  o[kNeck] = {0, 0, neck * h};
  o[kHead] = {0, 0, head * h};
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? 1.0 : -1.0;  // +y is the body's left
    const int hip = side == 0 ? kLeftHip : kRightHip;
    o[hip] = {0, s * hip_half * h, 0};
    o[hip + 1] = {0, 0, -kLen.thigh * h};  // knee
    o[hip + 2] = {0, 0, -kLen.shank * h};  // ankle, 0.039 H above the ground
    o[hip + 3] = rig::kToeOffset * h;      // metatarsophalangeal joint
    const int shoulder = side == 0 ? kLeftShoulder : kRightShoulder;
    o[shoulder] = {0, s * shoulder_half * h, neck * h};
    o[shoulder + 1] = {0, 0, -kLen.upper_arm * h};  // elbow
    o[shoulder + 2] = {0, 0, -kLen.forearm * h};    // wrist
  }
  return o;
}

}  // namespace ptnet
