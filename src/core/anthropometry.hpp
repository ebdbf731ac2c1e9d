// core/anthropometry.hpp: published body proportions, in one place.
//
//   const auto& p = ptnet::anthropometry::kDrillisContini;
//   double thigh_m = p.thigh * height_m;
//
// Sources (see docs/anthropometry.md):
//  - segment lengths as fractions of standing height H: Drillis & Contini
//    (1966), as reproduced in Winter, Biomechanics and Motor Control of Human
//    Movement, Fig. 4.1;
//  - segment mass fractions: de Leva (1996), adjustments to
//    Zatsiorsky-Seluyanov, by sex;
//  - whole-body density ~1050 kg/m^3.
// The motion stage (retargeting) and the body stage (geometry, masses) both
// read these tables, so a skeleton and the body built on it always agree.
//
// Private to the library (not installed): the stages include it as
// "core/anthropometry.hpp".
#pragma once

namespace ptnet::anthropometry {

// Landmark heights and segment lengths, fractions of standing height.
struct LengthFractions {
  double eye = 0.936, chin = 0.870, shoulder = 0.818, chest = 0.720, elbow = 0.630;
  double hip = 0.530, wrist = 0.485, fingertip = 0.377, knee = 0.285, ankle = 0.039;
  double shoulder_width = 0.259, hip_width = 0.191;
  double upper_arm = 0.186, forearm = 0.146, hand = 0.108;
  double thigh = 0.245, shank = 0.246;
  double foot_length = 0.152, foot_width = 0.055;
};
inline constexpr LengthFractions kDrillisContini{};

// Where along the foot (fraction of foot length, from the back of the heel)
// the ankle joint centre and the metatarsophalangeal (toe) joint lie, and the
// regions of the plantar surface (docs/anthropometry.md).
struct FootFractions {
  double ankle = 0.22;        // ankle joint centre above this point
  double mtp = 0.74;          // metatarsal heads / toe joint
  double heel_end = 0.30;     // heel pad 0-0.30
  double midfoot_end = 0.60;  // midfoot 0.30-0.60 (medial arch raised)
  double toes_start = 0.80;   // toes 0.80-1.0
  double mtp_height = 0.009;  // toe joint centre above the ground, fraction of H
};
inline constexpr FootFractions kFoot{};

// Segment masses, percent of body mass (de Leva 1996). One side each for the
// limbs; the sum over all segments with both sides is 100 %.
struct MassPercent {
  double head_neck, trunk, upper_trunk, middle_trunk, lower_trunk;
  double upper_arm, forearm, hand, thigh, shank, foot;
};
inline constexpr MassPercent kDeLevaFemale{6.68, 42.57, 15.45, 14.65, 12.47, 2.55, 1.38, 0.56,
                                           14.78, 4.81, 1.29};
inline constexpr MassPercent kDeLevaMale{6.94, 43.46, 15.96, 16.33, 11.17, 2.71, 1.62, 0.61,
                                         14.16, 4.33, 1.37};

inline constexpr double kTissueDensity = 1050.0;  // kg/m^3, whole-body average
inline constexpr double kGravity = 9.81;          // m/s^2

}  // namespace ptnet::anthropometry
