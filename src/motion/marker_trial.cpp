// A marker recording prepared for the joints: its unit checked against the
// data, the lab's vertical found, the map's markers taken as tracks (metres,
// world axes) and their short gaps filled.
#include <algorithm>
#include <cmath>
#include <limits>

#include "markers_internal.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"
#include "rotation.hpp"

namespace ptnet::detail {
namespace {

using V = Eigen::Vector3d;


// The median distance between the two ASIS markers (file units); NaN when
// no frame has both.
double median_asis_width(const Trc& trc, const ResolvedMap& r) {
  std::vector<double> w;
  const int a = r.marker[kRAsis], b = r.marker[kLAsis];
  for (int f = 0; f < trc.frames(); ++f)
    if (has(trc.at(f, a)) && has(trc.at(f, b))) w.push_back((trc.at(f, a) - trc.at(f, b)).norm());
  return w.empty() ? NAN : quantile(std::move(w), 0.5);
}

// The units a width of `width` file units is a human pelvis in ("" : none).
std::string fitting_unit(double width) {
  for (Units u : {Units::mm, Units::cm, Units::m, Units::in})
    if (kPelvisWidthM.contains(width * unit_metres(u))) return units_name(u);
  return "";
}

// The lab's vertical axis, from the pelvis standing above the heels.
UpAxis vertical_axis(const Trc& trc, const ResolvedMap& r) {
  V d = V::Zero();
  const int asis = r.marker[kRAsis];
  const int heel = r.marker[sided(kHeel, 0)];
  for (int f = 0; f < trc.frames(); ++f)
    if (has(trc.at(f, asis)) && has(trc.at(f, heel))) d += trc.at(f, asis) - trc.at(f, heel);
  int axis = 0;
  d.cwiseAbs().maxCoeff(&axis);
  if (axis == 0 || !(d[axis] > 0))
    throw Error::in(trc.source, std::string("expected the pelvis above the heels along +Y or +Z (the lab's vertical), found ") +
                                    (d[axis] < 0 ? "-" : "+") + "XYZ"[axis]);
  return axis == 1 ? UpAxis::y : UpAxis::z;
}

// Every marker the resolved map uses, once.
std::vector<int> used_markers(const ResolvedMap& r) {
  std::vector<int> used;
  for (int m : r.marker) if (m >= 0) used.push_back(m);
  for (const auto& s : r.set) used.insert(used.end(), s.begin(), s.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  return used;
}

}  // namespace

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

double trial_scale(const Trc& trc, const ResolvedMap& r, double given_mpu, double fallback_mpu) {
  const double width = median_asis_width(trc, r);
  if (!std::isfinite(width))
    throw Error::in(trc.source, "no frame has both ASIS markers (" + escaped(trc.markers[std::size_t(r.marker[kRAsis])]) +
                                    ", " + escaped(trc.markers[std::size_t(r.marker[kLAsis])]) + ")");
  const double scale = given_mpu > 0 ? given_mpu : trc.metres_per_unit;
  if (kPelvisWidthM.contains(width * scale)) return scale;
  if (fallback_mpu > 0 && kPelvisWidthM.contains(width * fallback_mpu)) return fallback_mpu;
  const std::string fits = fitting_unit(width);
  throw Error::in(trc.source, "the ASIS markers are " + number_text(width * scale) + " m apart " +
                                  (given_mpu > 0 ? "in the unit given (" + field_text("units") + ")"
                                                 : "in its Units (" + number_text(trc.metres_per_unit) + " m)") +
                                  ", expected a pelvis " + kPelvisWidthM.text() + " m wide" +
                                  (fits.empty() ? std::string(": the map's ASIS markers are not the pelvis?")
                                                : "; the values fit " + fits + ": pass " + field_text("units")));
}

PreparedTrial prepare_trial(const Trc& trc, const ResolvedMap& r, double scale, double max_gap_s) {
  PreparedTrial p;
  p.source = trc.source;
  p.start_s = trc.time_s.front();
  p.metres_per_unit = scale;
  p.up = vertical_axis(trc, r);
  p.asis_width_m = median_asis_width(trc, r) * scale;
  const std::vector<int> used = used_markers(r);
  Tracks& t = p.t;
  t.frames = trc.frames();
  t.rate_hz = trc.rate_hz;
  std::vector<int> track_of(trc.markers.size(), -1);
  for (int m : used) {
    track_of[std::size_t(m)] = t.count();
    t.names.push_back(trc.markers[std::size_t(m)]);
    auto& xyz = t.xyz.emplace_back(std::size_t(t.frames));
    for (int f = 0; f < t.frames; ++f) xyz[std::size_t(f)] = to_world(scale * trc.at(f, m), p.up).cast<float>();
  }
  for (int k = 0; k < kLandmarkCount; ++k)
    p.m.landmark[std::size_t(k)] = r.marker[std::size_t(k)] >= 0 ? track_of[std::size_t(r.marker[std::size_t(k)])] : -1;
  for (int s = 0; s < kSetCount; ++s)
    for (int m : r.set[std::size_t(s)]) p.m.set[std::size_t(s)].push_back(track_of[std::size_t(m)]);
  p.long_gaps.resize(std::size_t(t.count()));
  for (int u = 0; u < t.count(); ++u) p.filled += fill_gaps(t, u, max_gap_s, &p.long_gaps[std::size_t(u)]);
  return p;
}

void drop_empty_tracks(PreparedTrial& p) {
  for (int u = 0; u < p.t.count(); ++u) {
    const auto& g = p.long_gaps[std::size_t(u)];
    if (g.size() != 1 || g[0].begin != 0 || g[0].end != p.t.frames) continue;  // it has samples
    for (int& k : p.m.landmark) if (k == u) k = -1;
    for (auto& s : p.m.set) s.erase(std::remove(s.begin(), s.end(), u), s.end());
  }
}

}  // namespace ptnet::detail
