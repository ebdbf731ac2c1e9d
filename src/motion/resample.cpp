// Resampling a BVH to a new frame rate: position channels linearly, each
// joint's rotation as a quaternion slerp (shortest arc), written back as
// Euler angles in the joint's own channel order. Angles are unwrapped to
// stay near the source frame's (the two Euler solutions and 360-degree
// turns are tried), so curves stay continuous. Output frames at the source
// sample times reproduce the source values exactly.
#include <cmath>
#include <vector>

#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "rotation.hpp"

namespace ptnet {
namespace {

double unwrap_near(double deg, double ref) { return deg + 360.0 * std::round((ref - deg) / 360.0); }

struct RotationLayout {
  int cols[3];
  int axes[3];
};

// Joints with three distinct rotation axes are slerped; any other rotation
// channels (one or two axes) are interpolated linearly, as are positions.
void split_channels(const Bvh& bvh, std::vector<RotationLayout>& slerped, std::vector<int>& linear) {
  for (const BvhJoint& j : bvh.joints) {
    RotationLayout r{};
    int k = 0;
    for (std::size_t c = 0; c < j.channels.size(); ++c) {
      const int col = j.first_channel + int(c);
      if (!detail::is_rotation(j.channels[c])) {
        linear.push_back(col);
      } else if (k < 3) {
        r.cols[k] = col;
        r.axes[k] = detail::channel_axis(j.channels[c]);
        ++k;
      }
    }
    if (k == 3) {
      slerped.push_back(r);
    } else {
      for (std::size_t c = 0; c < j.channels.size(); ++c)
        if (detail::is_rotation(j.channels[c])) linear.push_back(j.first_channel + int(c));
    }
  }
}

Eigen::Quaterniond quat(const double* row, const RotationLayout& r) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (int k = 0; k < 3; ++k)
    q = q * Eigen::Quaterniond(Eigen::AngleAxisd(row[r.cols[k]] * detail::kDegToRad, Eigen::Vector3d::Unit(r.axes[k])));
  return q;
}

// One joint's rotation at fraction `a` between rows r0 and r1 (degrees, into
// dst): the slerp, written as the Euler angles nearest the linear blend of
// the source angles (where no wrap happens, the nearest representation).
void slerp_joint(const double* r0, const double* r1, double a, const RotationLayout& r, double* dst) {
  const Eigen::Quaterniond q = quat(r0, r).slerp(a, quat(r1, r));
  const Eigen::Vector3d e = detail::euler_angles(q.toRotationMatrix(), r.axes[0], r.axes[1], r.axes[2]) *
                            detail::kRadToDeg;
  double ref[3];
  for (int k = 0; k < 3; ++k) ref[k] = (1 - a) * r0[r.cols[k]] + a * r1[r.cols[k]];
  const double cand[2][3] = {{e[0], e[1], e[2]}, {e[0] + 180, 180 - e[1], e[2] + 180}};
  double best = 1e300;
  for (const auto& c : cand) {
    double v[3], cost = 0;
    for (int k = 0; k < 3; ++k) {
      v[k] = unwrap_near(c[k], ref[k]);
      cost += std::abs(v[k] - ref[k]);
    }
    if (cost < best) {
      best = cost;
      for (int k = 0; k < 3; ++k) dst[r.cols[k]] = v[k];
    }
  }
}

}  // namespace

Bvh resample(const Bvh& bvh, double fps) {
  if (!(fps > 0) || !std::isfinite(fps))
    throw Error::in(bvh.source, "resample: expected a positive frame rate");
  const int F = bvh.frames();
  if (F < 1) throw Error::in(bvh.source, "resample: no frames");
  Bvh out = bvh;
  out.frame_time = 1.0 / fps;
  const double duration = (F - 1) * bvh.frame_time;
  const double frames_out = std::floor(duration * fps + 1e-6) + 1;
  const std::size_t cc = std::size_t(bvh.channel_count);
  // An implausible Frame Time (hours per frame) must not exhaust memory.
  if (frames_out * double(cc) > 2e8)
    throw Error::in(bvh.source, "resampling " + std::to_string(F) + " frames of " +
                                    std::to_string(bvh.frame_time) + " s to " +
                                    std::to_string(fps) + " fps would make " +
                                    std::to_string(std::llround(frames_out)) +
                                    " frames; check Frame Time");
  const int n = int(frames_out);
  out.values.assign(std::size_t(n) * cc, 0.0);
  std::vector<RotationLayout> slerped;
  std::vector<int> linear;
  split_channels(bvh, slerped, linear);
  for (int f = 0; f < n; ++f) {
    const double s = f / fps / bvh.frame_time;  // source frame index (fractional)
    int i = int(std::floor(s + 1e-9));
    double a = s - i;
    if (i >= F - 1) {
      i = F - 1;
      a = 0;
    }
    if (a < 1e-9) a = 0;
    if (a > 1 - 1e-9) {
      ++i;
      a = 0;
    }
    double* dst = out.values.data() + std::size_t(f) * cc;
    const double* r0 = bvh.frame(i);
    if (a == 0) {
      std::copy(r0, r0 + cc, dst);
      continue;
    }
    const double* r1 = bvh.frame(i + 1);
    for (int col : linear) dst[col] = (1 - a) * r0[col] + a * r1[col];
    for (const RotationLayout& r : slerped) slerp_joint(r0, r1, a, r, dst);
  }
  return out;
}

}  // namespace ptnet
