// The static (standing) trial: read once, checked to be of the trial's
// marker set and scale; it rebuilds the landmarks the trial lacks (Cappozzo
// et al. 1995), gives the stature and levels the feet. The stature of a
// trial without one: from its frames.
#include <algorithm>
#include <cmath>

#include "core/anthropometry.hpp"
#include "markers_internal.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::detail {
namespace {

using V = Eigen::Vector3d;

constexpr double kMaxScaleRatio = 1.25;  // static / trial ASIS width (either way): the same subject and unit
constexpr double kMarkerBaseM = 0.030;   // a foot marker's centre above the floor (radius and base)
constexpr double kHeelMarkerM = 0.035;   // the heel marker's centre above the floor, standing, less kMarkerBaseM's
                                         // share: a straight leg's hip-heel distance + this is the hip height
constexpr double kLongestLegQuantile = 0.95;  // the frames where the legs are straightest


std::vector<V> mean_positions(const Tracks& t) {
  std::vector<V> mean;
  for (int u = 0; u < t.count(); ++u) {
    V sum = V::Zero();
    int n = 0;
    for (int f = 0; f < t.frames; ++f)
      if (t.has(f, u)) sum += t.at(f, u).cast<double>(), ++n;
    mean.push_back(n ? V(sum / n) : V::Constant(NAN));
  }
  return mean;
}

// Each foot's pitch correction [left, right] from the standing trial: the
// canonical rest pitch of the ankle -> toe bone less its median pitch
// there (the markers' toe joint is rarely where the canonical foot has it:
// a bone steeper or flatter than the sole it stands on).
std::array<double, 2> foot_pitch(const Tracks& t, const TrackMap& m, double h) {
  std::array<std::vector<double>, 2> pitch;
  for (int f = 0; f < t.frames; ++f) {
    const Pose p = joints_from_landmarks(landmarks_at(t, m, f), h, nullptr);
    for (int s = 0; s < 2; ++s) {
      const V d = p[s ? kRightToe : kLeftToe] - p[s ? kRightAnkle : kLeftAnkle];
      pitch[std::size_t(s)].push_back(std::atan2(-d.z(), d.head<2>().norm()));
    }
  }
  std::array<double, 2> out{};
  for (int s = 0; s < 2; ++s)
    out[std::size_t(s)] = std::clamp(rest_foot_pitch() - quantile(pitch[std::size_t(s)], 0.5), -0.5, 0.5);
  return out;
}

// The static trial's track holding the trial's track u (by name, else by key).
int static_track(const Tracks& st, const std::string& name) {
  for (int u = 0; u < st.count(); ++u)
    if (st.names[std::size_t(u)] == name) return u;
  const std::string key = marker_key(name);
  for (int u = 0; u < st.count(); ++u)
    if (marker_key(st.names[std::size_t(u)]) == key) return u;
  return -1;
}

// The clusters that carry landmark `lm` from the static trial into the
// trial: each segment's markers both have, at their standing positions.
std::vector<Cluster> static_clusters(int lm, const PreparedTrial& trial, const StaticTrial& st) {
  std::vector<Cluster> out;
  const V target = st.mean[std::size_t(st.p.m.landmark[std::size_t(lm)])];
  const auto trial_sets = segment_tracks(lm, trial.m);
  const auto static_sets = segment_tracks(lm, st.p.m);
  for (std::size_t k = 0; k < trial_sets.size() && k < static_sets.size(); ++k) {
    Cluster c{trial_sets[k].name, {}, {}, target};
    const std::vector<int>& in_static = static_sets[k].tracks;
    for (int u : trial_sets[k].tracks) {
      const int s = static_track(st.p.t, trial.t.names[std::size_t(u)]);
      if (s < 0 || std::find(in_static.begin(), in_static.end(), s) == in_static.end()) continue;
      if (!has(st.mean[std::size_t(s)])) continue;
      c.members.push_back(u);
      c.ref.push_back(st.mean[std::size_t(s)]);
    }
    if (c.members.size() >= 3) out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

StaticTrial read_static_trial(const std::string& path, const MarkerMap& map, const PreparedTrial& trial,
                              double given_mpu, double max_gap_s) {
  const Trc trc = read_trc(path);
  const ResolvedMap r = resolve(map, trc.markers);
  if (!r.problem.empty()) throw Error::in(path, r.problem);
  const auto missing = missing_landmarks(r, map);
  if (!missing.empty())
    throw Error::in(path, "the static trial is not of the trial's marker set: map '" + map.name +
                              "' (which places " + trial.source + ") lacks " + bounded_list(missing, 600, "; ", 200) +
                              " in it");
  StaticTrial st;
  st.p = prepare_trial(trc, r, trial_scale(trc, r, 0, given_mpu), max_gap_s);
  const double ratio = st.p.asis_width_m / trial.asis_width_m;
  if (!(ratio <= kMaxScaleRatio && ratio >= 1 / kMaxScaleRatio))
    throw Error::in(path, "the static trial's ASIS markers are " + fixed_text(st.p.asis_width_m, 3) + " m apart, " +
                              trial.source + "'s " + fixed_text(trial.asis_width_m, 3) +
                              " m: another subject, or the Units of one of them wrong?");
  drop_empty_tracks(st.p);
  st.mean = mean_positions(st.p.t);
  st.stature_m = stature_from_frames(st.p.t, st.p.m, 0.5);
  st.foot_pitch = foot_pitch(st.p.t, st.p.m, st.stature_m);
  return st;
}

std::vector<std::string> calibrate(PreparedTrial& trial, const StaticTrial& st, double max_gap_s) {
  std::vector<std::string> rebuilt;
  for (int lm = 0; lm < kLandmarkCount; ++lm) {
    const int su = st.p.m.landmark[std::size_t(lm)];
    if (trial.m.landmark[std::size_t(lm)] >= 0 || su < 0 || !has(st.mean[std::size_t(su)])) continue;
    const std::vector<Cluster> clusters = static_clusters(lm, trial, st);
    if (clusters.empty()) continue;
    Tracks& t = trial.t;
    std::vector<Eigen::Vector3f> xyz(std::size_t(t.frames));
    std::vector<int> unplaced;
    for (int f = 0; f < t.frames; ++f) {
      const V p = rebuild(t, f, clusters);
      xyz[std::size_t(f)] = p.cast<float>();
      if (!has(p)) unplaced.push_back(f);
    }
    if (!unplaced.empty()) throw_unplaced(trial, lm, "", unplaced, clusters, max_gap_s);
    trial.m.landmark[std::size_t(lm)] = t.count();
    t.names.push_back(st.p.t.names[std::size_t(su)]);
    t.xyz.push_back(std::move(xyz));
    trial.long_gaps.emplace_back();
    rebuilt.push_back(landmark_name(lm) + " (" + clusters.front().name + ")");
  }
  return rebuilt;
}

double stature_from_frames(const Tracks& t, const TrackMap& m, double q) {
  std::vector<double> hip, foot;
  for (int f = 0; f < t.frames; ++f) {
    const LandmarkFrame lm = landmarks_at(t, m, f);
    const auto hips = hip_centres(lm);
    if (has(hips[0]) && has(hips[1])) hip.push_back(0.5 * (hips[0].z() + hips[1].z()));
    double low = INFINITY;
    for (int side = 0; side < 2; ++side)
      for (int k : {kHeel, kMt1, kMt5, kToe, kToeTip})
        if (has(lm[std::size_t(sided(k, side))])) low = std::min(low, lm[std::size_t(sided(k, side))].z());
    if (std::isfinite(low)) foot.push_back(low);
  }
  const double floor_z = quantile(std::move(foot), 0.05) - kMarkerBaseM;
  const double h = (quantile(std::move(hip), q) - floor_z) / anthropometry::kDrillisContini.hip;
  return std::isfinite(h) ? h : 1.75;
}

double stature_from_legs(const Tracks& t, const TrackMap& m) {
  std::vector<double> leg;
  for (int f = 0; f < t.frames; ++f) {
    const LandmarkFrame lm = landmarks_at(t, m, f);
    const auto hips = hip_centres(lm);
    double longest = NAN;
    for (int side = 0; side < 2; ++side) {
      const V& heel = lm[std::size_t(sided(kHeel, side))];
      if (has(hips[std::size_t(side)]) && has(heel)) longest = std::fmax(longest, (hips[std::size_t(side)] - heel).norm());
    }
    if (std::isfinite(longest)) leg.push_back(longest);
  }
  const double h = (quantile(std::move(leg), kLongestLegQuantile) + kHeelMarkerM) / anthropometry::kDrillisContini.hip;
  return std::isfinite(h) ? h : 1.75;
}

}  // namespace ptnet::detail
