// Test helpers: foot sole points and ground contacts of a Motion, computed
// from joint positions only (the way a reader of the BVH would).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "ptnet/motion.hpp"

namespace ptnet::testing {

struct SolePoints {
  Eigen::Vector3d heel, tip;
};

// Heel back and toe tip of foot `side` (0 left, 1 right): rigid in the frame
// of ankle -> toe with the foot's lateral axis horizontal (no foot roll, as
// the generator makes them).
inline SolePoints sole_points(const Pose& p, int side) {
  const int ankle = side ? kRightAnkle : kLeftAnkle, toe = side ? kRightToe : kLeftToe;
  const Eigen::Vector3d fwd = p[toe] - p[ankle];
  const double h = fwd.norm() / std::hypot(0.07904, 0.030);
  const Eigen::Vector3d u = fwd.normalized();
  const Eigen::Vector3d lat = Eigen::Vector3d::UnitZ().cross(u).normalized();
  const Eigen::Vector3d w = u.cross(lat);
  const Eigen::Vector3d u0 = Eigen::Vector3d(0.07904, 0, -0.030).normalized();
  const Eigen::Vector3d w0 = u0.cross(Eigen::Vector3d::UnitY());
  auto map = [&](const Eigen::Vector3d& r) { return Eigen::Vector3d(r.dot(u0) * u + r.dot(w0) * w); };
  return {p[ankle] + h * map({-0.03344, 0, -0.039}), p[ankle] + h * map({0.11856, 0, -0.039})};
}

struct Contact {
  int side, first, last;  // frames, inclusive
  double heel_slip = 0, tip_slip = 0;  // m, horizontal range of a grounded point
  double min_z = 1e9, max_z = -1e9;    // m, lowest sole point over the contact
};

// A foot is in contact when its heel or toe tip is within `band` of the
// ground and moving horizontally slower than `speed` m/s. Contacts shorter
// than 3 frames are ignored.
inline std::vector<Contact> foot_contacts(const Motion& m, double band = 0.025, double speed = 0.2) {
  std::vector<Contact> out;
  const int n = m.size();
  for (int side = 0; side < 2; ++side) {
    std::vector<SolePoints> pts(n);
    for (int f = 0; f < n; ++f) pts[f] = sole_points(m.frames[f], side);
    auto hspeed = [&](int f, bool heel) {
      const int a = std::max(0, f - 1), b = std::min(n - 1, f + 1);
      if (a == b) return 0.0;
      const Eigen::Vector3d d = heel ? Eigen::Vector3d(pts[b].heel - pts[a].heel) : Eigen::Vector3d(pts[b].tip - pts[a].tip);
      return d.head<2>().norm() * m.fps / (b - a);
    };
    std::vector<char> on(n);
    for (int f = 0; f < n; ++f)
      on[f] = (pts[f].heel.z() < band && hspeed(f, true) < speed) ||
              (pts[f].tip.z() < band && hspeed(f, false) < speed);
    for (int f = 0; f < n;) {
      if (!on[f]) { ++f; continue; }
      int g = f;
      while (g + 1 < n && on[g + 1]) ++g;
      if (g - f + 1 >= 3) {
        Contact c{side, f, g};
        Eigen::Vector2d h0(1e9, 1e9), t0(1e9, 1e9);
        for (int k = f; k <= g; ++k) {
          const double low = std::min(pts[k].heel.z(), pts[k].tip.z());
          c.min_z = std::min(c.min_z, low);
          c.max_z = std::max(c.max_z, low);
          if (pts[k].heel.z() < 0.01) {
            if (h0.x() > 1e8) h0 = pts[k].heel.head<2>();
            c.heel_slip = std::max(c.heel_slip, (pts[k].heel.head<2>() - h0).norm());
          }
          if (pts[k].tip.z() < 0.01) {
            if (t0.x() > 1e8) t0 = pts[k].tip.head<2>();
            c.tip_slip = std::max(c.tip_slip, (pts[k].tip.head<2>() - t0).norm());
          }
        }
        out.push_back(c);
      }
      f = g + 1;
    }
  }
  std::sort(out.begin(), out.end(), [](const Contact& a, const Contact& b) { return a.first < b.first; });
  return out;
}

inline double lowest_sole_z(const Pose& p) {
  double z = 1e9;
  for (int s = 0; s < 2; ++s) {
    const SolePoints sp = sole_points(p, s);
    z = std::min({z, sp.heel.z(), sp.tip.z()});
  }
  return z;
}

}  // namespace ptnet::testing
