// The body model: segment masses (de Leva 1996), capsule radii from mass and
// tissue density, posing on the canonical skeleton, centre of mass.
#include "ptnet/body.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "core/anthropometry.hpp"
#include "foot_sole.hpp"
#include "ptnet/error.hpp"

namespace ptnet {
namespace {

// Volume (m^3) of a tapered capsule: a conical frustum of length `length`
// between end radii ra, rb, closed by two hemispheres.
double capsule_volume(double length, double ra, double rb) {
  return M_PI * length / 3 * (ra * ra + ra * rb + rb * rb) +
         2.0 / 3.0 * M_PI * (ra * ra * ra + rb * rb * rb);
}

// Mean radius r such that the capsule with end radii (1 + taper) r and
// (1 - taper) r has `volume` (bisection; the volume grows with r).
double solve_radius(double volume, double length, double taper) {
  double lo = 0, hi = 1;
  for (int it = 0; it < 60; ++it) {
    double mid = 0.5 * (lo + hi);
    if (capsule_volume(length, (1 + taper) * mid, (1 - taper) * mid) < volume) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

Eigen::Vector3d unit_or(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback) {
  double n = v.norm();
  return n > 1e-9 ? Eigen::Vector3d(v / n) : fallback;
}

Eigen::Vector3d distal_point(const SegmentShape& s, const Pose& pose) {
  Eigen::Vector3d b = pose[s.joint_b];
  if (s.extension_m > 0)
    b += unit_or(pose[s.joint_b] - pose[s.dir_from], Eigen::Vector3d(0, 0, 1)) * s.extension_m;
  return b;
}

// Hindfoot and toe patches of one foot. Sole frame: forward = the ankle->toe
// direction raised by its rest pitch, left = normal of the knee-ankle-toe plane
// (the body's left for either foot), up = forward x left.
std::array<SolePatch, 2> foot_patches(const SoleSurface& sole, const Eigen::Vector3d& knee,
                                      const Eigen::Vector3d& ankle, const Eigen::Vector3d& toe,
                                      double medial_sign) {
  const Eigen::Vector3d z(0, 0, 1);
  Eigen::Vector3d u = unit_or(toe - ankle, Eigen::Vector3d(1, 0, 0));
  Eigen::Vector3d l0 = (knee - ankle).cross(u);
  if (l0.norm() < 1e-9) l0 = z.cross(u);
  if (l0.norm() < 1e-9) l0 = Eigen::Vector3d(0, 1, 0);
  Eigen::Vector3d l = unit_or(l0 - l0.dot(u) * u, Eigen::Vector3d(0, 1, 0));
  Eigen::Vector3d n = u.cross(l);
  // Rest pitch of ankle->toe below the sole plane.
  const double fwd = (sole.mtp_u - sole.ankle_u) * sole.length_m;
  const double drop = sole.ankle_height_m - anthropometry::kFoot.mtp_height * (sole.length_m / anthropometry::kDrillisContini.foot_length);
  const double a0 = std::atan2(drop, fwd);
  Eigen::Vector3d f = std::cos(a0) * u + std::sin(a0) * n;
  Eigen::Vector3d up = -std::sin(a0) * u + std::cos(a0) * n;

  std::array<SolePatch, 2> p;
  p[0].origin = ankle - up * sole.ankle_height_m;
  p[0].forward = f;
  p[0].left = l;
  p[0].up = up;
  p[0].u_origin = sole.ankle_u;
  p[0].u_begin = 0;
  p[0].u_end = sole.mtp_u;
  p[0].medial_sign = medial_sign;
  // Toes hinge at the metatarsophalangeal joint: they follow the foot when it
  // is dorsiflexed (heel strike). When the heel rises they bend up against
  // the foot: level, or, with the joint above the ground (z = 0), pitched
  // down until the toe tip rests on the ground, as the ground reaction
  // dorsiflexes them in push-off; never beyond the line of the foot.
  Eigen::Vector3d ft = f;
  p[1].origin = p[0].origin + f * fwd;
  if (f.z() < 0) {
    const Eigen::Vector3d level = unit_or(Eigen::Vector3d(f.x(), f.y(), 0), f);
    const double toe_len = (1 - sole.mtp_u) * sole.length_m;
    const double s = std::clamp(p[1].origin.z() / toe_len, 0.0, -f.z());  // sine of the toes' pitch
    ft = unit_or(std::sqrt(1 - s * s) * level - s * z, f);
  }
  Eigen::Vector3d lt = unit_or(l - l.dot(ft) * ft, l);
  p[1].forward = ft;
  p[1].left = lt;
  p[1].up = ft.cross(lt);
  p[1].u_origin = sole.mtp_u;
  p[1].u_begin = sole.mtp_u;
  p[1].u_end = 1.0;
  p[1].medial_sign = medial_sign;
  return p;
}

}  // namespace

double Body::bmi() const { return mass_kg() / (height_m() * height_m()); }

Body::Body(const BodySpec& spec) : spec_(spec) {
  validate(spec_);
  namespace A = anthropometry;
  const auto& len = A::kDrillisContini;
  const auto& pct = spec_.sex == Sex::male ? A::kDeLevaMale : A::kDeLevaFemale;
  const double h = height_m();
  const double foot_len = std::hypot(0.0790, 0.030) * h;  // ankle -> toe joint

  struct Def {
    int seg, a, b, dir;
    double ext_frac, percent, length_frac, taper;
    bool ground;
  };
  // taper: radius (1 + taper) r at the proximal end, (1 - taper) r distal.
  const Def defs[] = {
      {kSegHeadNeck, kNeck, kHead, kNeck, 0.130, pct.head_neck, 0.052 + 0.130, -0.2, true},
      {kSegUpperTrunk, kChest, kNeck, kChest, 0, pct.upper_trunk, 0.098, 0.0, true},
      {kSegMiddleTrunk, kSpine, kChest, kSpine, 0, pct.middle_trunk, 0.120, 0.0, true},
      {kSegLowerTrunk, kPelvis, kSpine, kPelvis, 0, pct.lower_trunk, 0.070, 0.0, true},
      {kSegLeftUpperArm, kLeftShoulder, kLeftElbow, kLeftShoulder, 0, pct.upper_arm, len.upper_arm, 0.15, true},
      {kSegLeftForearm, kLeftElbow, kLeftWrist, kLeftElbow, 0, pct.forearm, len.forearm, 0.2, true},
      {kSegLeftHand, kLeftWrist, kLeftWrist, kLeftElbow, len.hand, pct.hand, len.hand, 0.1, true},
      {kSegRightUpperArm, kRightShoulder, kRightElbow, kRightShoulder, 0, pct.upper_arm, len.upper_arm, 0.15, true},
      {kSegRightForearm, kRightElbow, kRightWrist, kRightElbow, 0, pct.forearm, len.forearm, 0.2, true},
      {kSegRightHand, kRightWrist, kRightWrist, kRightElbow, len.hand, pct.hand, len.hand, 0.1, true},
      {kSegLeftThigh, kLeftHip, kLeftKnee, kLeftHip, 0, pct.thigh, len.thigh, 0.2, true},
      {kSegLeftShank, kLeftKnee, kLeftAnkle, kLeftKnee, 0, pct.shank, len.shank, 0.25, true},
      {kSegLeftFoot, kLeftAnkle, kLeftToe, kLeftAnkle, 0, pct.foot, foot_len / h, 0.0, false},
      {kSegRightThigh, kRightHip, kRightKnee, kRightHip, 0, pct.thigh, len.thigh, 0.2, true},
      {kSegRightShank, kRightKnee, kRightAnkle, kRightKnee, 0, pct.shank, len.shank, 0.25, true},
      {kSegRightFoot, kRightAnkle, kRightToe, kRightAnkle, 0, pct.foot, foot_len / h, 0.0, false},
  };
  double total_percent = 0;
  for (const auto& d : defs) total_percent += d.percent;
  for (const auto& d : defs) {
    SegmentShape& s = segments_[d.seg];
    s.joint_a = d.a;
    s.joint_b = d.b;
    s.dir_from = d.dir;
    s.extension_m = d.ext_frac * h;
    // de Leva's percentages sum to 100 +- 0.01: normalise so masses sum to the weight.
    s.mass_kg = spec_.weight_kg * d.percent / total_percent;
    double r = solve_radius(s.mass_kg / A::kTissueDensity, d.length_frac * h, d.taper);
    s.radius_a_m = (1 + d.taper) * r;
    s.radius_b_m = (1 - d.taper) * r;
    s.touches_ground = d.ground;
  }
  sole_ = detail::make_sole_surface(spec_);
}

PosedBody pose_body(const Body& body, const Pose& pose) {
  PosedBody out;
  for (int s = 0; s < kSegmentCount; ++s) {
    const auto& seg = body.segments()[s];
    out.a[s] = pose[seg.joint_a];
    out.b[s] = distal_point(seg, pose);
  }
  out.left_foot = foot_patches(body.sole(), pose[kLeftKnee], pose[kLeftAnkle], pose[kLeftToe], -1.0);
  out.right_foot = foot_patches(body.sole(), pose[kRightKnee], pose[kRightAnkle], pose[kRightToe], +1.0);
  return out;
}

Eigen::Vector3d centre_of_mass(const Body& body, const Pose& pose) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double mass = 0;
  for (const auto& seg : body.segments()) {
    sum += seg.mass_kg * 0.5 * (pose[seg.joint_a] + distal_point(seg, pose));
    mass += seg.mass_kg;
  }
  return sum / mass;
}

}  // namespace ptnet
