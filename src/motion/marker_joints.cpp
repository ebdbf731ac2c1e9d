// The canonical joints of one frame from its anatomical landmarks (world,
// metres, z up). The methods, and where a landmark is missing the offsets
// that stand in for it, are in docs/markers.md; H is the stature.
//
//  pelvis     ISB frame from the ASIS and the PSIS midpoint (or the sacral
//             marker); hip joint centres by Harrington et al. (2007):
//             posterior 0.24 PD + 9.9 mm, inferior 0.30 PW + 10.9 mm,
//             lateral 0.33 PW + 7.3 mm (PW: inter-ASIS, PD: ASIS to PSIS
//             midpoints); the pelvis joint is their midpoint.
//  knee       epicondyle midpoint; lateral only: medially by half the knee
//             breadth (0.0275 H); none: the hip-ankle triangle with thigh
//             0.245 H and shank 0.246 H, the knee forward.
//  ankle      malleolus midpoint; lateral only: medially by half the ankle
//             breadth (0.0195 H); none: above the heel marker (forward
//             0.0334 H, up 0.039 H less the marker's 25 mm).
//  toe        the metatarsophalangeal joint: the metatarsal-head markers'
//             midpoint (or the toe marker) 10 mm down (marker radius and skin).
//  trunk      neck at the acromia midpoint (else the C7 / clavicle midpoint,
//             else the sternum marker 0.04 H back and 0.03 H up); spine and
//             chest on the pelvis -> neck line at the canonical fractions.
//             No trunk marker (a lower-body set): the trunk upright, the
//             neck 0.288 H above the pelvis joint, the shoulders level.
//  shoulder   acromion lowered by 0.17 x the biacromial breadth (Rab et al.
//             2002); without the marker, 0.13 H lateral to the neck.
//  elbow, wrist  as the knee (breadth 0.039 H) and the marker midpoint; none:
//             hanging down the trunk axis.
//  head       0.052 H from the neck towards the head top marker (else the
//             head or temple markers' mean).
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/anthropometry.hpp"
#include "markers_internal.hpp"

namespace ptnet::detail {
namespace {

using V = Eigen::Vector3d;
namespace A = anthropometry;

V mid(const V& a, const V& b) { return 0.5 * (a + b); }
V unit(const V& v, const V& fallback) {
  const double n = v.norm();
  return n > 1e-9 ? V(v / n) : fallback;
}
// The part of `v` normal to the unit vector `axis`, as a unit vector.
V normal_to(const V& v, const V& axis, const V& fallback) { return unit(v - v.dot(axis) * axis, fallback); }

// The middle joint of a two-bone chain a - j - b with bone lengths l1, l2,
// bent towards `towards` (a direction); straight along a -> b when out of reach.
V chain_middle(const V& a, const V& b, double l1, double l2, const V& towards) {
  const double d = (b - a).norm();
  const V e = unit(b - a, V(0, 0, -1));
  if (d >= l1 + l2 || d < 1e-6) return a + e * (l1 / (l1 + l2)) * std::max(d, 1e-6);
  const double along = (d * d + l1 * l1 - l2 * l2) / (2 * d);
  const double off = std::sqrt(std::max(0.0, l1 * l1 - along * along));
  return a + along * e + off * normal_to(towards, e, V(1, 0, 0));
}

// A joint centre between a lateral and a medial marker; with one of them,
// moved by half the breadth along `medial` (made normal to the segment axis
// `axis`). NaN when both are missing.
V joint_centre(const V& lat, const V& med, double half_breadth, const V& medial, const V& axis) {
  if (has(lat) && has(med)) return mid(lat, med);
  const V m = normal_to(medial, axis, medial);
  if (has(lat)) return lat + half_breadth * m;
  if (has(med)) return med - half_breadth * m;
  return V::Constant(NAN);
}

struct Pelvis {
  V origin, anterior, superior, right;
  V hip[2];  // [right, left]
};

Pelvis pelvis_frame(const LandmarkFrame& lm) {
  const V& ra = lm[kRAsis];
  const V& la = lm[kLAsis];
  V back = lm[kSacrum];
  if (has(lm[kRPsis]) && has(lm[kLPsis])) back = mid(lm[kRPsis], lm[kLPsis]);
  else if (!has(back)) back = has(lm[kRPsis]) ? lm[kRPsis] : lm[kLPsis];
  Pelvis p;
  p.origin = mid(ra, la);
  p.right = unit(ra - la, V(0, -1, 0));
  p.anterior = normal_to(p.origin - back, p.right, V(1, 0, 0));
  p.superior = p.right.cross(p.anterior);
  const double pw = (ra - la).norm(), pd = (p.origin - back).norm();
  for (int s = 0; s < 2; ++s) {
    const double lateral = (s == 0 ? 1 : -1) * (0.33 * pw + 0.0073);
    p.hip[s] = p.origin + p.anterior * (-0.24 * pd - 0.0099) + p.superior * (-0.30 * pw - 0.0109) + p.right * lateral;
  }
  return p;
}

// The neck from the trunk markers; NaN without any (a lower-body set).
V neck_point(const LandmarkFrame& lm, const Pelvis& p, double h) {
  const V& rs = lm[sided(kShoulder, 0)];
  const V& ls = lm[sided(kShoulder, 1)];
  if (has(rs) && has(ls)) return mid(rs, ls);
  if (has(lm[kC7]) && has(lm[kClav])) return mid(lm[kC7], lm[kClav]);
  for (int k : {kC7, kClav}) if (has(lm[k])) return lm[k];
  if (has(lm[kSternum])) return lm[kSternum] - 0.04 * h * p.anterior + 0.03 * h * p.superior;
  if (!has(rs) && !has(ls)) return V::Constant(NAN);
  const V& one = has(rs) ? rs : ls;
  return one - (one - p.origin).dot(p.right) * p.right;
}

V head_reference(const LandmarkFrame& lm) {
  if (has(lm[kHeadTop])) return lm[kHeadTop];
  V sum = V::Zero();
  int n = 0;
  for (int side = 0; side < 2; ++side)
    for (int k : {kHeadFront, kHeadBack, kTemple})
      if (has(lm[sided(k, side)])) sum += lm[sided(k, side)], ++n;
  return n ? V(sum / n) : V::Constant(NAN);
}

void place_leg(const LandmarkFrame& lm, const Pelvis& p, int side, double h, Pose& out) {
  const int hip_j = side == 0 ? kRightHip : kLeftHip;
  const V hip = p.hip[side];
  const V medial = side == 0 ? V(-p.right) : p.right;
  const V& heel = lm[sided(kHeel, side)];
  V toe_ref = lm[sided(kToe, side)];
  const V &mt1 = lm[sided(kMt1, side)], &mt5 = lm[sided(kMt5, side)], &tip = lm[sided(kToeTip, side)];
  if (has(mt1) && has(mt5)) toe_ref = mid(mt1, mt5);
  else if (!has(toe_ref)) toe_ref = has(mt1) ? mt1 : has(mt5) ? mt5 : V(heel + A::kFoot.mtp * (tip - heel));
  const V fwd = unit(toe_ref - heel, p.anterior);
  const V foot_up = normal_to(V(0, 0, 1), fwd, V(0, 0, 1));
  const V knee_lat = lm[sided(kKneeLat, side)], knee_med = lm[sided(kKneeMed, side)];
  const V thigh_axis = unit((has(knee_lat) ? knee_lat : knee_med) - hip, V(0, 0, -1));
  V knee = joint_centre(knee_lat, knee_med, 0.0275 * h, medial, thigh_axis);
  const V ankle_lat = lm[sided(kAnkleLat, side)], ankle_med = lm[sided(kAnkleMed, side)];
  const V shank_from = has(knee) ? knee : hip;
  V ankle = joint_centre(ankle_lat, ankle_med, 0.0195 * h, medial,
                         unit((has(ankle_lat) ? ankle_lat : ankle_med) - shank_from, V(0, 0, -1)));
  if (!has(ankle))
    ankle = heel + 0.0334 * h * fwd + (A::kDrillisContini.ankle * h - 0.025) * foot_up;
  if (!has(knee))
    knee = chain_middle(hip, ankle, A::kDrillisContini.thigh * h, A::kDrillisContini.shank * h, fwd);
  out[hip_j] = hip;
  out[hip_j + 1] = knee;
  out[hip_j + 2] = ankle;
  out[hip_j + 3] = toe_ref - 0.010 * foot_up;
}

// `right`: the shoulders' lateral direction without an acromion marker.
void place_arm(const LandmarkFrame& lm, const Pelvis& p, int side, double h, const V& neck, const V& trunk_up,
               const V& right, double shoulder_drop, Pose& out) {
  const int sh = side == 0 ? kRightShoulder : kLeftShoulder;
  const V medial = side == 0 ? V(-p.right) : p.right;
  const V& acromion = lm[sided(kShoulder, side)];
  const V shoulder = has(acromion) ? V(acromion - shoulder_drop * trunk_up)
                                   : V(neck + (side == 0 ? 1 : -1) * right * (0.5 * A::kDrillisContini.shoulder_width * h));
  const V &el = lm[sided(kElbowLat, side)], &em = lm[sided(kElbowMed, side)];
  const V &wl = lm[sided(kWristLat, side)], &wm = lm[sided(kWristMed, side)];
  V wrist = has(wl) && has(wm) ? mid(wl, wm) : has(wl) ? wl : wm;
  const V upper_axis = unit((has(el) ? el : em) - shoulder, -trunk_up);
  V elbow = joint_centre(el, em, 0.0195 * h, medial, upper_axis);
  const double upper = A::kDrillisContini.upper_arm * h, fore = A::kDrillisContini.forearm * h;
  if (!has(elbow))
    elbow = has(wrist) ? chain_middle(shoulder, wrist, upper, fore, -p.anterior) : V(shoulder - upper * trunk_up);
  if (!has(wrist)) wrist = elbow - fore * trunk_up;
  out[sh] = shoulder;
  out[sh + 1] = elbow;
  out[sh + 2] = wrist;
}

}  // namespace

std::array<V, 2> hip_centres(const LandmarkFrame& lm) {
  const Pelvis p = pelvis_frame(lm);
  return {p.hip[0], p.hip[1]};
}

Pose joints_from_landmarks(const LandmarkFrame& lm, double h, std::vector<std::string>* methods) {
  const Pelvis p = pelvis_frame(lm);
  Pose out;
  out[kPelvis] = mid(p.hip[0], p.hip[1]);
  V neck = neck_point(lm, p, h);
  const bool assumed = !has(neck);  // no trunk marker: upright above the pelvis
  if (assumed) neck = out[kPelvis] + (A::kDrillisContini.shoulder - A::kDrillisContini.hip) * h * V(0, 0, 1);
  const V right = assumed ? normal_to(p.right, V(0, 0, 1), p.right) : p.right;
  const V trunk_up = unit(neck - out[kPelvis], p.superior);
  const double span = A::kDrillisContini.shoulder - A::kDrillisContini.hip;  // pelvis -> neck, 0.288 H
  out[kSpine] = out[kPelvis] + (0.070 / span) * (neck - out[kPelvis]);
  out[kChest] = out[kPelvis] + ((A::kDrillisContini.chest - A::kDrillisContini.hip) / span) * (neck - out[kPelvis]);
  out[kNeck] = neck;
  const V head_ref = head_reference(lm);
  const V head_dir = has(head_ref) ? unit(head_ref - neck, trunk_up) : trunk_up;
  out[kHead] = neck + (A::kDrillisContini.chin - A::kDrillisContini.shoulder) * h * head_dir;
  const V &rs = lm[sided(kShoulder, 0)], &ls = lm[sided(kShoulder, 1)];
  const double drop = has(rs) && has(ls) ? 0.17 * (rs - ls).norm() : 0.0;
  for (int side = 0; side < 2; ++side) {
    place_leg(lm, p, side, h, out);
    place_arm(lm, p, side, h, neck, trunk_up, right, drop, out);
  }
  if (methods) {
    auto how = [&](int lat, int med, const char* name, const char* none) {
      for (int side = 0; side < 2; ++side) {
        const bool l = has(lm[sided(lat, side)]), m = has(lm[sided(med, side)]);
        methods->push_back(std::string(side == 0 ? "right " : "left ") + name + ": " +
                           (l && m ? "marker midpoint" : l ? "lateral marker + half breadth" : m ? "medial marker + half breadth" : none));
      }
    };
    methods->push_back("hips: Harrington 2007 from the ASIS and the " +
                       std::string(has(lm[kRPsis]) && has(lm[kLPsis]) ? "PSIS" : "sacral marker"));
    if (assumed)
      methods->push_back("trunk: assumed (no trunk marker): upright, the neck 0.288 H above the pelvis joint, "
                         "the shoulders level 0.259 H apart, the arms hanging");
    how(kKneeLat, kKneeMed, "knee", "hip-ankle triangle");
    how(kAnkleLat, kAnkleMed, "ankle", "offset from the heel marker");
    how(kElbowLat, kElbowMed, "elbow", has(lm[sided(kWristLat, 0)]) || has(lm[sided(kWristMed, 0)]) ? "shoulder-wrist triangle" : "hanging");
    methods->push_back(std::string("shoulders: ") + (drop > 0 ? "Rab 2002 below the acromia" : "from the neck"));
    methods->push_back(std::string("head: ") + (has(head_ref) ? "towards the head markers" : "along the trunk"));
  }
  return out;
}

}  // namespace ptnet::detail
