// Marker tracks: short gaps filled, landmarks rebuilt on their segment's
// markers (a rigid fit of a reference pose), the landmarks of a frame.
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "markers_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::detail {
namespace {

using V = Eigen::Vector3d;
using Vf = Eigen::Vector3f;

constexpr double kMinSpreadM = 1e-3;  // a cluster's markers must span more than a line (2nd singular value, m)

void hermite(Tracks& t, int u, int a, int b) {
  const int F = t.frames;
  const Vf p0 = t.at(a, u), p1 = t.at(b, u);
  const float span = float(b - a);
  const Vf m0 = (a >= 1 && t.has(a - 1, u) ? Vf(p0 - t.at(a - 1, u)) : Vf((p1 - p0) / span)) * span;
  const Vf m1 = (b + 1 < F && t.has(b + 1, u) ? Vf(t.at(b + 1, u) - p1) : Vf((p1 - p0) / span)) * span;
  for (int k = a + 1; k < b; ++k) {
    const float s = float(k - a) / span, s2 = s * s, s3 = s2 * s;
    t.at(k, u) = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
  }
}

}  // namespace

int fill_gaps(Tracks& t, int u, double max_gap_s, std::vector<Gap>* long_gaps) {
  const int max_frames = int(std::floor(max_gap_s * t.rate_hz + 1e-9));
  const int F = t.frames;
  int filled = 0;
  for (int f = 0; f < F;) {
    if (t.has(f, u)) {
      ++f;
      continue;
    }
    int end = f;
    while (end < F && !t.has(end, u)) ++end;  // gap [f, end)
    if (end - f > max_frames || (f == 0 && end == F)) {
      if (long_gaps) long_gaps->push_back({f, end});
    } else if (f == 0 || end == F) {
      const Vf v = f == 0 ? t.at(end, u) : t.at(f - 1, u);
      for (int k = f; k < end; ++k) t.at(k, u) = v;
      filled += end - f;
    } else {
      hermite(t, u, f - 1, end);
      filled += end - f;
    }
    f = end;
  }
  return filled;
}

V rebuild(const Tracks& t, int f, const std::vector<Cluster>& clusters) {
  for (const Cluster& c : clusters) {
    std::vector<int> use;
    for (std::size_t k = 0; k < c.members.size(); ++k)
      if (std::isfinite(c.ref[k].x()) && t.has(f, c.members[k])) use.push_back(int(k));
    if (use.size() < 3) continue;
    Eigen::Matrix3Xd ref(3, Eigen::Index(use.size())), now(3, Eigen::Index(use.size()));
    for (std::size_t k = 0; k < use.size(); ++k) {
      ref.col(Eigen::Index(k)) = c.ref[std::size_t(use[k])];
      now.col(Eigen::Index(k)) = t.at(f, c.members[std::size_t(use[k])]).cast<double>();
    }
    const Eigen::Matrix3Xd centred = ref.colwise() - ref.rowwise().mean();
    if (Eigen::JacobiSVD<Eigen::Matrix3Xd>(centred).singularValues()(1) < kMinSpreadM) continue;
    const Eigen::Matrix4d fit = Eigen::umeyama(ref, now, false);
    return (fit * c.target.homogeneous()).head<3>();
  }
  return V::Constant(NAN);
}

std::vector<Segment> segment_tracks(int landmark, const TrackMap& m) {
  auto with = [&](std::vector<int> set, std::initializer_list<int> landmarks) {
    for (int lm : landmarks) {
      const int u = m.landmark[std::size_t(lm)];
      if (u >= 0 && std::find(set.begin(), set.end(), u) == set.end()) set.push_back(u);
    }
    return set;
  };
  if (landmark < kSided) {
    if (landmark > kSacrum) return {};
    return {{"pelvis", with({}, {kRAsis, kLAsis, kRPsis, kLPsis, kSacrum})}};
  }
  const int side = (landmark - kSided) / kPerSide;
  const int lm = landmark - side * kPerSide;
  auto set = [&](int s) { return Segment{set_name(side * kSetsPerSide + s), m.set[std::size_t(side * kSetsPerSide + s)]}; };
  Segment foot = set(kFoot);
  foot.tracks = with(foot.tracks, {sided(kHeel, side), sided(kMt1, side), sided(kMt5, side), sided(kToe, side),
                                   sided(kToeTip, side)});
  if (lm == kKneeLat || lm == kKneeMed) return {set(kThigh), set(kShank)};
  if (lm == kAnkleLat || lm == kAnkleMed) return {set(kShank), foot};
  if (lm == kHeel || lm == kMt1 || lm == kMt5 || lm == kToe || lm == kToeTip) return {foot};
  return {};
}

std::string frame_ranges(const std::vector<int>& frames) {
  std::string out;
  int ranges = 0;
  for (std::size_t i = 0; i < frames.size();) {
    std::size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    if (++ranges > 4) return out + ", ...";
    out += (out.empty() ? "" : ", ") + std::to_string(frames[i] + 1) +
           (j > i ? "-" + std::to_string(frames[j] + 1) : std::string());
    i = j + 1;
  }
  return out;
}

void throw_unplaced(const PreparedTrial& p, int landmark, const std::string& marker, const std::vector<int>& frames,
                    const std::vector<Cluster>& clusters, double max_gap_s) {
  const double t0 = p.start_s + frames.front() / p.t.rate_hz, t1 = p.start_s + frames.back() / p.t.rate_hz;
  std::vector<std::string> segments;
  for (const Cluster& c : clusters) segments.push_back(c.name);
  const std::string frames_text = "frames " + frame_ranges(frames) + " (" + fixed_text(t0, 3) + "-" + fixed_text(t1, 3) + " s)";
  std::string what;
  if (marker.empty())
    what = landmark_name(landmark) + " (rebuilt from the static trial) cannot be placed in " + frames_text +
           ": fewer than 3 markers of " + join(segments, " or ") + " there";
  else
    what = "marker " + escaped(marker) + " (" + landmark_name(landmark) + ") is missing in " + frames_text +
           "; gaps up to " + number_text(max_gap_s) + " s are filled" +
           (segments.empty() ? std::string() : ", longer ones rebuilt on 3 markers of " + join(segments, " or ") + ", too few there");
  throw Error::in(p.source, what);
}

LandmarkFrame landmarks_at(const Tracks& t, const TrackMap& m, int f) {
  LandmarkFrame lm;
  for (int k = 0; k < kLandmarkCount; ++k) {
    const int u = m.landmark[std::size_t(k)];
    lm[std::size_t(k)] = u >= 0 ? V(t.at(f, u).cast<double>()) : V::Constant(NAN);
  }
  return lm;
}

}  // namespace ptnet::detail
