// The generator's kinematic model: trunk and arm FK from joint angles, legs
// by two-bone inverse kinematics onto prescribed foot poses (rig.hpp).
#include "rig.hpp"

#include <algorithm>
#include <cmath>

namespace ptnet::rig {

using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

Matrix3d rot_x(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitX()).toRotationMatrix(); }
Matrix3d rot_y(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitY()).toRotationMatrix(); }
Matrix3d rot_z(double a) { return Eigen::AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix(); }

// Rotating an upward bone about +y by +a tips it forward (+x); about +x by
// -a tips it to the left (+y).
Matrix3d trunk_rotation(double yaw, double pitch, double roll) {
  return rot_z(yaw) * rot_y(pitch) * rot_x(-roll);
}

// The foot points forward-down from the ankle; about +y by -a lifts the toes.
Matrix3d foot_rotation(double yaw, double pitch) { return rot_z(yaw) * rot_y(-pitch); }

FootPose planted_foot(const Vector2d& xy, double yaw, double pitch, double h) {
  FootPose f;
  const Vector3d flat_ankle(xy.x(), xy.y(), detail::kLen.ankle * h);
  f.rotation = foot_rotation(yaw, pitch);
  if (pitch == 0) {
    f.ankle = flat_ankle;
    return f;
  }
  const Vector3d pivot = (pitch > 0 ? kHeelPoint : kToeTipPoint) * h;
  const Vector3d pivot_world = flat_ankle + rot_z(yaw) * pivot;
  f.ankle = pivot_world - f.rotation * pivot;
  return f;
}

Vector3d heel_point(const FootPose& foot, double h) { return foot.ankle + foot.rotation * kHeelPoint * h; }
Vector3d toe_tip_point(const FootPose& foot, double h) {
  return foot.ankle + foot.rotation * kToeTipPoint * h;
}
double foot_lowest_z(const FootPose& foot, double h) {
  return std::min(heel_point(foot, h).z(), toe_tip_point(foot, h).z());
}

namespace {

const int kHip[2] = {kLeftHip, kRightHip};
const int kShoulder[2] = {kLeftShoulder, kRightShoulder};

double height_of(const Pose& offsets) { return offsets[kPelvis].z() / detail::kLen.hip; }

Matrix3d pelvis_rotation(const Controls& c) { return trunk_rotation(c.yaw, c.pitch, c.roll); }

// Knee position for hip -> ankle with thigh a, shank b, bending towards `pole`.
Vector3d solve_knee(const Vector3d& hip, const Vector3d& ankle, double a, double b, const Vector3d& pole) {
  Vector3d d = ankle - hip;
  double dist = d.norm();
  const Vector3d u = dist > 1e-9 ? Vector3d(d / dist) : Vector3d(-Vector3d::UnitZ());
  dist = std::clamp(dist, std::abs(a - b) + 1e-6, a + b - 1e-9);
  const double cos_hip = std::clamp((a * a + dist * dist - b * b) / (2 * a * dist), -1.0, 1.0);
  Vector3d perp = pole - pole.dot(u) * u;
  if (perp.norm() < 1e-9) perp = Vector3d::UnitX() - u.x() * u;
  perp.normalize();
  return hip + a * (cos_hip * u + std::sqrt(1 - cos_hip * cos_hip) * perp);
}

}  // namespace

double max_pelvis_z(const Controls& c, const Pose& offsets, double straight) {
  const Matrix3d rp = pelvis_rotation(c);
  double best = 1e9;
  for (int s = 0; s < 2; ++s) {
    const double leg = straight * (offsets[kHip[s] + 1].norm() + offsets[kHip[s] + 2].norm());
    const Vector3d hip_rel = rp * offsets[kHip[s]];  // hip relative to the pelvis
    const Vector2d horiz = c.pelvis.head<2>() + hip_rel.head<2>() - c.foot[s].ankle.head<2>();
    const double reach2 = leg * leg - horiz.squaredNorm();
    const double z = c.foot[s].ankle.z() - hip_rel.z() + std::sqrt(std::max(reach2, 0.0));
    best = std::min(best, z);
  }
  return best;
}

Pose evaluate(const Controls& c, const Pose& o) {
  Pose p;
  const Matrix3d rp = pelvis_rotation(c);
  p[kPelvis] = c.pelvis;
  const Matrix3d half = trunk_rotation(0.5 * c.trunk_yaw, 0.5 * c.trunk_pitch, 0.5 * c.trunk_roll);
  const Matrix3d r_spine = rp * half;
  const Matrix3d r_chest = r_spine * half;
  const Matrix3d r_neck = r_chest * rot_z(c.head_yaw) * rot_y(c.head_pitch);
  p[kSpine] = p[kPelvis] + rp * o[kSpine];
  p[kChest] = p[kSpine] + r_spine * o[kChest];
  p[kNeck] = p[kChest] + r_chest * o[kNeck];
  p[kHead] = p[kNeck] + r_neck * o[kHead];

  for (int s = 0; s < 2; ++s) {
    const double side = s == 0 ? 1.0 : -1.0;
    // Leg: hip from the pelvis, ankle and toe from the foot pose, knee by IK
    // bending forward along the foot and pelvis headings, a little outward.
    const int hip = kHip[s];
    p[hip] = p[kPelvis] + rp * o[hip];
    const FootPose& f = c.foot[s];
    // (The foot's heading alone: it turns continuously, so the knee never flips.)
    Vector3d pole = f.rotation.col(0);
    pole.z() = 0;
    pole = pole.normalized() + 0.15 * side * Vector3d(-pole.y(), pole.x(), 0).normalized();
    p[hip + 1] = solve_knee(p[hip], f.ankle, o[hip + 1].norm(), o[hip + 2].norm(), pole);
    p[hip + 2] = p[hip + 1] + o[hip + 2].norm() * (f.ankle - p[hip + 1]).normalized();
    p[hip + 3] = p[hip + 2] + f.rotation * (kToeOffset * height_of(o));

    // Arm: shoulder swing towards the commanded direction, elbow hinge.
    const Arm& a = c.arm[s];
    const int sh = kShoulder[s];
    const Vector3d dir = rot_z(-side * a.horiz) * rot_y(-a.flex) * rot_x(side * a.abd) * Vector3d(0, 0, -1);
    const Matrix3d r_sh =
        r_chest * Eigen::Quaterniond::FromTwoVectors(Vector3d(0, 0, -1), dir).toRotationMatrix();
    const Matrix3d r_el = r_sh * rot_y(-a.elbow);
    p[sh] = p[kChest] + r_chest * o[sh];
    p[sh + 1] = p[sh] + r_sh * o[sh + 1];
    p[sh + 2] = p[sh + 1] + r_el * o[sh + 2];
  }
  return p;
}

void settle_pelvis_heights(std::vector<Controls>& frames, const std::vector<double>& nominal,
                           const Pose& offsets, double fps) {
  const int n = int(frames.size());
  std::vector<double> z(n), eroded(n);
  for (int f = 0; f < n; ++f) z[f] = std::min(nominal[f], max_pelvis_z(frames[f], offsets));
  const int r = std::max(1, int(std::lround(0.1 * fps)));
  for (int f = 0; f < n; ++f) {
    double m = z[f];
    for (int g = std::max(0, f - r); g <= std::min(n - 1, f + r); ++g) m = std::min(m, z[g]);
    eroded[f] = m;
  }
  for (int f = 0; f < n; ++f) {
    double sum = 0;
    int count = 0;
    for (int g = f - r; g <= f + r; ++g) {
      sum += eroded[std::clamp(g, 0, n - 1)];
      ++count;
    }
    frames[f].pelvis.z() = std::min(sum / count, z[f]);
  }
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}
double min_jerk(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * x * (10 + x * (-15 + 6 * x));
}
double wrap_angle(double a) {
  a = std::fmod(a + kPi, 2 * kPi);
  if (a <= 0) a += 2 * kPi;
  return a - kPi;
}

Vector3d Spline::operator()(double t) const {
  const int n = int(keys_.size());
  if (n == 0) return Vector3d::Zero();
  if (t <= keys_.front().t) return keys_.front().v;
  if (t >= keys_.back().t) return keys_.back().v;
  int i = int(std::upper_bound(keys_.begin(), keys_.end(), t,
                               [](double x, const Key& k) { return x < k.t; }) -
              keys_.begin()) - 1;
  const Key& k0 = keys_[i];
  const Key& k1 = keys_[i + 1];
  auto tangent = [&](int j) -> Vector3d {
    if (j <= 0 || j >= n - 1) return Vector3d::Zero();  // ease in and out at the ends
    return (keys_[j + 1].v - keys_[j - 1].v) / (keys_[j + 1].t - keys_[j - 1].t);
  };
  const double dt = k1.t - k0.t;
  const double s = (t - k0.t) / dt;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * k0.v + (s3 - 2 * s2 + s) * dt * tangent(i) + (-2 * s3 + 3 * s2) * k1.v +
         (s3 - s2) * dt * tangent(i + 1);
}

namespace {
std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t a, std::uint64_t b, std::uint64_t c)
    : engine_(splitmix(splitmix(splitmix(splitmix(seed) ^ a) ^ b) ^ c)) {}
std::uint64_t Rng::bits() { return engine_(); }
double Rng::uniform(double lo, double hi) {
  return lo + (hi - lo) * (double(engine_() >> 11) * (1.0 / 9007199254740992.0));
}
double Rng::normal(double mean, double sd) {
  // Box-Muller on our own uniforms (std::normal_distribution differs by library).
  const double u1 = std::max(uniform(0, 1), 1e-300), u2 = uniform(0, 1);
  return mean + sd * std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}
int Rng::integer(int lo, int hi) { return lo + int(engine_() % std::uint64_t(hi - lo + 1)); }

}  // namespace ptnet::rig
