// Forward kinematics of a BVH rig: world joint positions (m, z up).
//
// Convention: a joint's local translation is OFFSET plus its position
// channels (displacements, as the iClone and CMU exports use them); its
// local rotation is the product of its rotation channels in file order.
// The per-joint channel layout is computed once per call; the frame loop
// does no allocation (>= 10^6 joint-frames/s on one core, bench_motion).
#include "fk.hpp"

#include <cmath>
#include <vector>

#include "motion_internal.hpp"
#include "ptnet/error.hpp"

namespace ptnet::detail {

FkLayout::FkLayout(const Bvh& bvh, double scale) : scale_(scale) {
  joints_.resize(bvh.joints.size());
  for (std::size_t j = 0; j < bvh.joints.size(); ++j) {
    const BvhJoint& src = bvh.joints[j];
    Layout& l = joints_[j];
    l.parent = src.parent;
    if (l.parent >= int(j))
      throw Error::in(bvh.source, "joint " + src.name + " listed before its parent");
    for (int a = 0; a < 3; ++a) l.offset[a] = src.offset[a] * scale;
    for (std::size_t c = 0; c < src.channels.size(); ++c) {
      const int col = src.first_channel + int(c);
      if (col >= bvh.channel_count)
        throw Error::in(bvh.source, "channel columns past the frame width");
      const Channel ch = src.channels[c];
      if (is_rotation(ch)) {
        if (l.rotations < 3) {
          l.rot_axis[l.rotations] = channel_axis(ch);
          l.rot_col[l.rotations] = col;
          ++l.rotations;
        }
      } else {
        l.pos_col[channel_axis(ch)] = col;
      }
    }
  }
}

void FkLayout::run(const double* frame, Eigen::Vector3d* positions,
                   Eigen::Matrix3d* rotations) const {
  const std::size_t n = joints_.size();
  if (scratch_.size() < n) scratch_.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Layout& l = joints_[j];
    double t[3] = {l.offset[0], l.offset[1], l.offset[2]};
    for (int a = 0; a < 3; ++a)
      if (l.pos_col[a] >= 0) t[a] += frame[l.pos_col[a]] * scale_;
    Frame& g = scratch_[j];
    if (l.parent < 0) {
      for (int a = 0; a < 3; ++a) g.p[a] = t[a];
      static constexpr double kI[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
      for (int a = 0; a < 9; ++a) g.r[a] = kI[a];
    } else {
      const Frame& pf = scratch_[std::size_t(l.parent)];
      const double* R = pf.r;  // column-major
      for (int a = 0; a < 3; ++a)
        g.p[a] = pf.p[a] + R[a] * t[0] + R[3 + a] * t[1] + R[6 + a] * t[2];
      for (int a = 0; a < 9; ++a) g.r[a] = R[a];
    }
    // Right-multiply by each elementary rotation: only two columns change.
    for (int k = 0; k < l.rotations; ++k) {
      const double ang = frame[l.rot_col[k]] * kDegToRad;
      const double c = std::cos(ang), s = std::sin(ang);
      double* r = g.r;
      int u, v;  // columns mixed: R*R_x mixes (1,2), R*R_y (2,0), R*R_z (0,1)
      switch (l.rot_axis[k]) {
        case 0:
          u = 1;
          v = 2;
          break;
        case 1:
          u = 2;
          v = 0;
          break;
        default:
          u = 0;
          v = 1;
          break;
      }
      for (int a = 0; a < 3; ++a) {
        const double cu = r[3 * u + a], cv = r[3 * v + a];
        r[3 * u + a] = c * cu + s * cv;
        r[3 * v + a] = -s * cu + c * cv;
      }
    }
    positions[j] = Eigen::Vector3d(g.p[0], g.p[1], g.p[2]);
    if (rotations) rotations[j] = Eigen::Map<const Eigen::Matrix3d>(g.r);
  }
}

}  // namespace ptnet::detail

namespace ptnet {

namespace {
void map_to_world(Eigen::Vector3d* p, std::size_t n, UpAxis up) {
  if (up == UpAxis::z) return;
  for (std::size_t i = 0; i < n; ++i) p[i] = detail::to_world(p[i], up);
}
}  // namespace

std::vector<Eigen::Vector3d> forward_kinematics(const Bvh& bvh, double scale, UpAxis up) {
  const detail::FkLayout layout(bvh, scale);
  const std::size_t J = bvh.joints.size();
  const int F = bvh.frames();
  std::vector<Eigen::Vector3d> out(std::size_t(F) * J);
  for (int f = 0; f < F; ++f) layout.run(bvh.frame(f), out.data() + std::size_t(f) * J);
  map_to_world(out.data(), out.size(), up);
  return out;
}

void forward_kinematics_frame(const Bvh& bvh, int frame, double scale, UpAxis up,
                              std::vector<Eigen::Vector3d>& out) {
  if (frame < 0 || frame >= bvh.frames())
    throw Error::in(bvh.source, "frame " + std::to_string(frame) + " out of range (0.." +
                                    std::to_string(bvh.frames() - 1) + ")");
  const detail::FkLayout layout(bvh, scale);
  const std::size_t start = out.size();
  out.resize(start + bvh.joints.size());
  layout.run(bvh.frame(frame), out.data() + start);
  map_to_world(out.data() + start, bvh.joints.size(), up);
}

}  // namespace ptnet
