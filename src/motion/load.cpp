// Motion files -> Motion on the canonical joints. BVH: units, mapping,
// leading T-pose, resampling, forward kinematics; then, for every loader,
// grounding and a treadmill belt removed.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "c3d_internal.hpp"
#include "markers_internal.hpp"
#include "ptnet/error.hpp"
#include "motion_internal.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {

Motion motion_from_bvh(const Bvh& source, const MotionOptions& options) {
  detail::check_read_fps(options);
  if (source.frames() < 1) throw Error::in(source.source, "no frames");
  const double scale = options.metres_per_unit > 0
                           ? options.metres_per_unit
                           : metres_per_unit(source, options.units, options.up);
  const std::array<int, kJointCount> map = map_canonical(source);

  const Bvh* bvh = &source;
  Bvh trimmed;
  if (!options.keep_tpose && source.frames() > 1 && is_tpose(source, 0, map, scale, options.up)) {
    trimmed = source;
    trimmed.values.erase(trimmed.values.begin(), trimmed.values.begin() + source.channel_count);
    bvh = &trimmed;
  }
  Bvh resampled;
  if (options.fps > 0 && !same_rate(bvh->fps(), options.fps)) {
    resampled = resample(*bvh, options.fps);
    bvh = &resampled;
  }

  Motion m;
  m.name = std::filesystem::path(source.source).stem().string();
  m.fps = options.fps > 0 ? options.fps : bvh->fps();
  if (!trimmed.joints.empty()) m.start_s = source.frame_time;  // the T-pose frame dropped
  const std::vector<Eigen::Vector3d> p = forward_kinematics(*bvh, scale, options.up);
  const std::size_t J = bvh->joints.size();
  m.frames.resize(std::size_t(bvh->frames()));
  for (std::size_t f = 0; f < m.frames.size(); ++f)
    for (int k = 0; k < kJointCount; ++k)
      m.frames[f][std::size_t(k)] = p[f * J + std::size_t(map[std::size_t(k)])];

  detail::ground(m);
  if (options.remove_belt) {
    const Eigen::Vector2d belt = treadmill_belt_velocity(m);
    if (belt.norm() > 0) m = without_belt(std::move(m), belt);
  }
  return m;
}

Motion load_motion(const std::string& path, const MotionOptions& options) {
  if (is_trc_path(path) || is_c3d_path(path)) return motion_from_trc(read_markers(path), options);
  return motion_from_bvh(read_bvh(path), options);
}

namespace detail {

void check_read_fps(const MotionOptions& options) {
  if (!std::isfinite(options.fps) || options.fps > 0) check_range("fps", options.fps, kReadFpsRange);
}

void ground(Motion& m) {
  if (m.frames.empty()) return;
  std::vector<double> lowest(m.frames.size());
  for (std::size_t f = 0; f < m.frames.size(); ++f) lowest[f] = lowest_foot_z(m.frames[f]);
  const std::size_t q = lowest.size() / 4;
  std::nth_element(lowest.begin(), lowest.begin() + std::ptrdiff_t(q), lowest.end());
  const double floor_z = lowest[q];
  for (Pose& pose : m.frames)
    for (Eigen::Vector3d& joint : pose) joint.z() -= floor_z;
}

Motion resample_linear(const Motion& motion, double fps) {
  Motion out = motion;
  out.fps = fps;
  out.frames.clear();
  const double duration = (motion.size() - 1) / motion.fps;
  const int T = int(std::floor(duration * fps + 1e-9)) + 1;
  for (int t = 0; t < T; ++t) {
    const double x = t / fps * motion.fps;
    const int i = std::min(int(x), motion.size() - 1);
    const int j = std::min(i + 1, motion.size() - 1);
    const double a = x - i;
    Pose p;
    for (int k = 0; k < kJointCount; ++k) p[k] = (1 - a) * motion.frames[i][k] + a * motion.frames[j][k];
    out.frames.push_back(p);
  }
  return out;
}

}  // namespace detail

}  // namespace ptnet
