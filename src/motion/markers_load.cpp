// motion_from_trc: a marker recording -> the canonical joints. Steps: choose
// and resolve the map; fill short gaps; rebuild from a static trial the
// landmarks the trial lacks; find the lab's vertical axis; joints per frame;
// resample; ground; remove a treadmill belt.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

#include <Eigen/Geometry>

#include "core/anthropometry.hpp"
#include "markers_internal.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

using V = Eigen::Vector3d;
using detail::ResolvedMap;

bool has(const V& v) { return std::isfinite(v.x()); }

std::string markers_found(const Trc& trc) {
  const std::size_t shown = std::min<std::size_t>(trc.markers.size(), 60);
  std::vector<std::string> names(trc.markers.begin(), trc.markers.begin() + std::ptrdiff_t(shown));
  return join(names, " ") + (shown < trc.markers.size() ? " ..." : "");
}

// The map of options.marker_map, or the shipped map that places the file
// (the one that finds most landmarks).
MarkerMap choose_map(const Trc& trc, const std::string& wanted, ResolvedMap& resolved) {
  if (!wanted.empty()) {
    MarkerMap map = marker_map(wanted);
    resolved = detail::resolve(map, trc);
    const auto missing = detail::missing_landmarks(resolved, map);
    if (!missing.empty())
      throw Error::in(trc.source, "marker map '" + map.name + "' cannot place the markers: it lacks " +
                                      join(missing, "; ") + "; the file has " + markers_found(trc));
    return map;
  }
  MarkerMap best;
  std::vector<std::string> best_missing;
  int best_found = -1;
  bool placed = false;
  for (const std::string& name : marker_map_names()) {
    MarkerMap map = marker_map(name);
    ResolvedMap r = detail::resolve(map, trc);
    const auto missing = detail::missing_landmarks(r, map);
    const bool ok = missing.empty();
    if ((ok && !placed) || (ok == placed && r.found > best_found)) {
      best = map, resolved = r, best_missing = missing, best_found = r.found, placed = ok;
    }
  }
  if (!placed)
    throw Error::in(trc.source, "no shipped marker map (" + join(marker_map_names(), ", ") +
                                    ") places the markers (closest, " + best.name + ", lacks " +
                                    join(best_missing, "; ") + "); the file has " + markers_found(trc) +
                                    "; describe them with a map file (docs/markers.md)");
  return best;
}

// Every marker the resolved map uses.
std::vector<int> used_markers(const ResolvedMap& r) {
  std::vector<int> used;
  for (int m : r.marker) if (m >= 0) used.push_back(m);
  for (const auto& s : r.set) used.insert(used.end(), s.begin(), s.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  return used;
}

}  // namespace

int detail::fill_gaps(Trc& trc, int m, double max_gap_s) {
  const int max_frames = int(std::floor(max_gap_s * trc.rate_hz + 1e-9));
  const int F = trc.frames();
  auto p = [&](int f) -> V& { return trc.xyz[std::size_t(f) * trc.markers.size() + std::size_t(m)]; };
  int filled = 0;
  for (int f = 0; f < F;) {
    if (has(p(f))) { ++f; continue; }
    int end = f;
    while (end < F && !has(p(end))) ++end;  // gap [f, end)
    const int n = end - f;
    if (f == 0 && end == F) throw Error::in(trc.source, "marker " + escaped(trc.markers[std::size_t(m)]) + " has no samples");
    if (n > max_frames)
      throw Error::in(trc.source, "marker " + escaped(trc.markers[std::size_t(m)]) + " is missing in frames " +
                                      std::to_string(f + 1) + "-" + std::to_string(end) + " (" +
                                      fixed_text(trc.time_s[std::size_t(f)], 3) + "-" +
                                      fixed_text(trc.time_s[std::size_t(end - 1)], 3) + " s); gaps up to " +
                                      number_text(max_gap_s) + " s are filled");
    if (f == 0 || end == F) {
      const V v = f == 0 ? p(end) : p(f - 1);
      for (int k = f; k < end; ++k) p(k) = v;
    } else {
      const int a = f - 1, b = end;  // known samples either side
      const V p0 = p(a), p1 = p(b);
      const double span = b - a;
      const V m0 = (a >= 1 && has(p(a - 1)) ? V(p0 - p(a - 1)) : V((p1 - p0) / span)) * span;
      const V m1 = (b + 1 < F && has(p(b + 1)) ? V(p(b + 1) - p1) : V((p1 - p0) / span)) * span;
      for (int k = f; k < end; ++k) {
        const double s = (k - a) / span, s2 = s * s, s3 = s2 * s;
        p(k) = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
      }
    }
    filled += n;
    f = end;
  }
  return filled;
}

namespace {

// Tracking set of a segment whose markers carry a missing landmark (in
// order of preference).
std::vector<int> tracking_sets_of(int landmark) {
  if (landmark < detail::kSided) return {};
  const int side = (landmark - detail::kSided) / detail::kPerSide;
  const int lm = landmark - side * detail::kPerSide;
  const int base = side * detail::kSetsPerSide;
  if (lm == detail::kKneeLat || lm == detail::kKneeMed) return {base + detail::kThigh, base + detail::kShank};
  if (lm == detail::kAnkleLat || lm == detail::kAnkleMed) return {base + detail::kShank, base + detail::kFoot};
  if (lm == detail::kHeel || lm == detail::kMt1 || lm == detail::kMt5 || lm == detail::kToe) return {base + detail::kFoot};
  return {};
}

// The landmarks the trial lacks and the static trial has, rebuilt on the
// segment's tracking markers (a rigid fit of their standing positions,
// Cappozzo et al. 1995), appended to trc as markers of the static trial's
// names. Returns the landmarks rebuilt.
std::vector<std::string> calibrate(Trc& trc, const MarkerMap& map, const ResolvedMap& r, const std::string& path) {
  Trc st = read_trc(path);
  const ResolvedMap rs = detail::resolve(map, st);
  std::vector<std::string> rebuilt;
  const std::size_t M0 = trc.markers.size();
  std::vector<V> extra_ref;                 // landmark in the static trial (mean)
  std::vector<std::vector<int>> extra_set;  // markers of the dynamic trial that carry it
  std::vector<Eigen::Matrix3Xd> extra_cluster;
  auto static_mean = [&](int m) {
    V sum = V::Zero();
    int n = 0;
    for (int f = 0; f < st.frames(); ++f)
      if (has(st.at(f, m))) sum += st.at(f, m), ++n;
    return n ? V(sum / n) : V::Constant(NAN);
  };
  for (int lm = 0; lm < detail::kLandmarkCount; ++lm) {
    if (r.marker[std::size_t(lm)] >= 0 || rs.marker[std::size_t(lm)] < 0) continue;
    const V ref = static_mean(rs.marker[std::size_t(lm)]);
    if (!has(ref)) continue;
    for (int set : tracking_sets_of(lm)) {
      std::vector<int> dyn;
      std::vector<V> stat;
      for (int m : rs.set[std::size_t(set)]) {
        const int d = trc.find(st.markers[std::size_t(m)]);
        const V s = static_mean(m);
        if (d >= 0 && has(s) && std::find(r.set[std::size_t(set)].begin(), r.set[std::size_t(set)].end(), d) !=
                                    r.set[std::size_t(set)].end())
          dyn.push_back(d), stat.push_back(s);
      }
      if (dyn.size() < 3) continue;
      Eigen::Matrix3Xd c(3, Eigen::Index(dyn.size()));
      for (std::size_t k = 0; k < dyn.size(); ++k) c.col(Eigen::Index(k)) = stat[k];
      const Eigen::Matrix3Xd centred = c.colwise() - c.rowwise().mean();
      if (Eigen::JacobiSVD<Eigen::Matrix3Xd>(centred).singularValues()(1) < 1e-3 / trc.metres_per_unit) continue;
      trc.markers.push_back(st.markers[std::size_t(rs.marker[std::size_t(lm)])]);
      extra_ref.push_back(ref);
      extra_set.push_back(dyn);
      extra_cluster.push_back(c);
      rebuilt.push_back(detail::landmark_name(lm) + " (" + detail::set_name(set) + ")");
      break;
    }
  }
  if (extra_ref.empty()) return rebuilt;
  const std::size_t M = trc.markers.size();
  std::vector<V> xyz(std::size_t(trc.frames()) * M);
  for (int f = 0; f < trc.frames(); ++f) {
    for (std::size_t m = 0; m < M0; ++m) xyz[std::size_t(f) * M + m] = trc.xyz[std::size_t(f) * M0 + m];
    for (std::size_t e = 0; e < extra_ref.size(); ++e) {
      Eigen::Matrix3Xd now(3, extra_cluster[e].cols());
      for (Eigen::Index k = 0; k < now.cols(); ++k) now.col(k) = trc.xyz[std::size_t(f) * M0 + std::size_t(extra_set[e][std::size_t(k)])];
      const Eigen::Matrix4d t = Eigen::umeyama(extra_cluster[e], now, false);
      xyz[std::size_t(f) * M + M0 + e] = (t * extra_ref[e].homogeneous()).head<3>();
    }
  }
  trc.xyz = std::move(xyz);
  return rebuilt;
}

// The lab's vertical axis (1: Y, 2: Z), from the pelvis standing above the heels.
int vertical_axis(const Trc& trc, const ResolvedMap& r) {
  V d = V::Zero();
  const int asis = r.marker[detail::kRAsis];
  const int heel = r.marker[detail::sided(detail::kHeel, 0)];
  for (int f = 0; f < trc.frames(); ++f) d += trc.at(f, asis) - trc.at(f, heel);
  int axis = 0;
  d.cwiseAbs().maxCoeff(&axis);
  if (axis == 0 || d[axis] < 0)
    throw Error::in(trc.source, std::string("expected the pelvis above the heels along +Y or +Z (the lab's vertical), found ") +
                                    (d[axis] < 0 ? "-" : "+") + "XYZ"[axis]);
  return axis;
}

// The stature (m) of the recorded subject, for the anthropometric offsets:
// the hip joint centres' median height above the floor, over the canonical
// hip height (0.530 H); the floor 30 mm (a marker's radius and base) below
// the low foot markers (5th percentile of the lowest per frame).
double stature(const std::vector<detail::LandmarkFrame>& lm) {
  std::vector<double> hip, foot;
  for (const auto& f : lm) {
    const Pose p = detail::joints_from_landmarks(f, 1.75, nullptr);
    hip.push_back(0.5 * (p[kLeftHip].z() + p[kRightHip].z()));
    double low = INFINITY;
    for (int side = 0; side < 2; ++side)
      for (int k : {detail::kHeel, detail::kMt1, detail::kMt5, detail::kToe, detail::kToeTip})
        if (has(f[std::size_t(detail::sided(k, side))])) low = std::min(low, f[std::size_t(detail::sided(k, side))].z());
    foot.push_back(low);
  }
  std::nth_element(hip.begin(), hip.begin() + std::ptrdiff_t(hip.size() / 2), hip.end());
  const std::size_t k = foot.size() / 20;
  std::nth_element(foot.begin(), foot.begin() + std::ptrdiff_t(k), foot.end());
  const double h = (hip[hip.size() / 2] - (foot[k] - 0.030)) / anthropometry::kDrillisContini.hip;
  return std::clamp(h, 0.5, 2.5);
}

// The landmarks of every frame: world axes (the lab's vertical up), metres.
std::vector<detail::LandmarkFrame> landmark_frames(const Trc& trc, const ResolvedMap& r, int up) {
  const double s = trc.metres_per_unit;
  std::vector<detail::LandmarkFrame> lm(std::size_t(trc.frames()));
  for (int f = 0; f < trc.frames(); ++f)
    for (int k = 0; k < detail::kLandmarkCount; ++k) {
      const int m = r.marker[std::size_t(k)];
      const V p = m >= 0 ? trc.at(f, m) : V::Constant(NAN);
      // Y up: (x, y, z)_lab -> (z, x, y)_world, as for a y-up BVH; Z up: as is.
      lm[std::size_t(f)][std::size_t(k)] = s * (up == 1 ? V(p.z(), p.x(), p.y()) : p);
    }
  return lm;
}

// Each foot's pitch correction [left, right] from the static trial, where the
// feet stand flat: the canonical rest pitch of the ankle -> toe bone less
// its median pitch there (the markers' toe joint is rarely where the
// canonical foot has it: a bone steeper or flatter than the sole it stands
// on). Zero without a static trial.
std::array<double, 2> static_foot_pitch(const std::string& path, const MarkerMap& map, const MotionOptions& o) {
  if (path.empty()) return {0, 0};
  Trc st = read_trc(path);
  const ResolvedMap r = detail::resolve(map, st);
  if (!detail::missing_landmarks(r, map).empty()) return {0, 0};
  for (int m : used_markers(r)) detail::fill_gaps(st, m, o.max_gap_s);
  const auto lm = landmark_frames(st, r, vertical_axis(st, r));
  const double h = stature(lm);
  std::array<std::vector<double>, 2> pitch;
  for (const auto& f : lm) {
    const Pose p = detail::joints_from_landmarks(f, h, nullptr);
    for (int s = 0; s < 2; ++s) {
      const V d = p[s ? kRightToe : kLeftToe] - p[s ? kRightAnkle : kLeftAnkle];
      pitch[std::size_t(s)].push_back(std::atan2(-d.z(), d.head<2>().norm()));
    }
  }
  std::array<double, 2> out{};
  for (int s = 0; s < 2; ++s) {
    auto& v = pitch[std::size_t(s)];
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    out[std::size_t(s)] = std::clamp(rest_foot_pitch() - v[v.size() / 2], -0.5, 0.5);
  }
  return out;
}

}  // namespace

Motion motion_from_trc(const Trc& input, const MotionOptions& options, MarkerReport* report) {
  detail::check_read_fps(options);
  if (input.frames() < 2) throw Error::in(input.source, "expected at least 2 frames, found " + std::to_string(input.frames()));
  check_range("max_gap_s", options.max_gap_s, Range{0, 10});
  Trc trc = input;
  ResolvedMap r;
  const MarkerMap map = choose_map(trc, options.marker_map, r);
  int filled = 0;
  for (int m : used_markers(r)) filled += detail::fill_gaps(trc, m, options.max_gap_s);
  std::vector<std::string> rebuilt;
  if (!options.static_markers.empty()) {
    rebuilt = calibrate(trc, map, r, options.static_markers);
    r = detail::resolve(map, trc);
  }
  const int up = vertical_axis(trc, r);
  const std::vector<detail::LandmarkFrame> lm = landmark_frames(trc, r, up);
  const double h = stature(lm);
  const std::array<double, 2> pitch = static_foot_pitch(options.static_markers, map, options);
  Motion m;
  m.name = std::filesystem::path(trc.source).stem().string();
  m.fps = trc.rate_hz;
  m.start_s = trc.time_s.front();
  std::vector<std::string> methods;
  for (std::size_t f = 0; f < lm.size(); ++f) {
    m.frames.push_back(detail::joints_from_landmarks(lm[f], h, f == 0 ? &methods : nullptr));
    pitch_feet(m.frames.back(), pitch);
  }
  if (!options.static_markers.empty())
    methods.push_back("toe joints: pitched to the canonical flat foot of the static trial (left " +
                      fixed_text(pitch[0] * 180 / M_PI, 1) + ", right " + fixed_text(pitch[1] * 180 / M_PI, 1) +
                      " degrees)");
  if (options.fps > 0 && !detail::same_rate(m.fps, options.fps)) m = detail::resample_linear(m, options.fps);
  if (options.fps > 0) m.fps = options.fps;
  detail::ground(m);
  Eigen::Vector2d belt = Eigen::Vector2d::Zero();
  if (options.remove_belt) {
    belt = treadmill_belt_velocity(m);
    if (belt.norm() > 0) m = without_belt(std::move(m), belt);
  }
  if (report) {
    report->map = map.name;
    report->placed.clear();
    for (int k = 0; k < detail::kLandmarkCount; ++k)
      if (r.marker[std::size_t(k)] >= 0) report->placed.push_back(detail::landmark_name(k));
    report->calibrated = rebuilt;
    report->methods = methods;
    report->gap_filled_frames = filled;
    report->up_axis = up == 1 ? "y" : "z";
    report->belt_speed_mps = belt.norm();
    report->stature_m = h;
  }
  return m;
}

}  // namespace ptnet
