// BVH file -> Motion on the canonical joints: units, mapping, leading
// T-pose, resampling, forward kinematics.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

namespace ptnet {

Motion motion_from_bvh(const Bvh& source, const MotionOptions& options) {
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
  if (options.fps > 0 && std::abs(options.fps - bvh->fps()) > 1e-4 * options.fps) {
    resampled = resample(*bvh, options.fps);
    bvh = &resampled;
  }

  Motion m;
  m.name = std::filesystem::path(source.source).stem().string();
  m.fps = bvh->fps();
  const std::vector<Eigen::Vector3d> p = forward_kinematics(*bvh, scale, options.up);
  const std::size_t J = bvh->joints.size();
  m.frames.resize(std::size_t(bvh->frames()));
  for (std::size_t f = 0; f < m.frames.size(); ++f)
    for (int k = 0; k < kJointCount; ++k)
      m.frames[f][std::size_t(k)] = p[f * J + std::size_t(map[std::size_t(k)])];

  // Ground: the floor is where the feet are in most frames. Its height is
  // the lower quartile of the per-frame lowest sole point: robust to
  // airborne phases and to stretches of feet through the floor (CMU 141_15
  // squats sink the toes 10 cm for a tenth of the clip).
  std::vector<double> lowest(m.frames.size());
  for (std::size_t f = 0; f < m.frames.size(); ++f) lowest[f] = lowest_foot_z(m.frames[f]);
  const std::size_t q = lowest.size() / 4;
  std::nth_element(lowest.begin(), lowest.begin() + std::ptrdiff_t(q), lowest.end());
  const double floor_z = lowest[q];
  for (Pose& pose : m.frames)
    for (Eigen::Vector3d& joint : pose) joint.z() -= floor_z;
  return m;
}

Motion load_motion(const std::string& path, const MotionOptions& options) {
  return motion_from_bvh(read_bvh(path), options);
}

}  // namespace ptnet
