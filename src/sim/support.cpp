// What carries the body: the floor under its feet and other parts, and a
// seat. Per frame of a placed motion, which surfaces touch the floor
// (floor_support); where the centre of mass's load stays off the feet's
// support without the body falling, something else carries part of it
// (seat_share).
#include <algorithm>
#include <cmath>

#include "core/smooth.hpp"
#include "sim_internal.hpp"

namespace ptnet::detail {
namespace {

constexpr double kOffSupportM = 0.05;  // m: the load's point this far outside the feet is carried by something else
constexpr double kCarriedMinS = 0.3;   // s: ... for at least this long (shorter: capture error, a stumble)
constexpr double kShareSmoothS = 0.1;  // s: Gaussian sigma of the feet's share (no step in the load)
constexpr double kCarriedShare = 0.98;  // a frame whose feet carry less is carried (MotionDynamics::carried)
// A seat carries only hips this low (fraction of stature above the floor):
// seated, the hip joints are ~0.30 H up (a 0.45 m chair), standing 0.53 H;
// a body whose load leaves its feet with the hips higher (an arabesque, a
// pirouette's spin) is the capture's or the point-mass model's error, not
// a seat.
constexpr double kSeatHipHeight = 0.40;

// Distance from p to the segment a-b (horizontal).
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        Eigen::Vector2d* nearest) {
  const Eigen::Vector2d d = b - a;
  const double s = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  *nearest = a + s * d;
  return (*nearest - p).norm();
}

// The distance from p to the convex hull of `points` (horizontal; 0 inside)
// and the hull's nearest point.
double hull_distance(const Eigen::Vector2d& p, std::vector<Eigen::Vector2d> points, Eigen::Vector2d* nearest) {
  // Andrew's monotone chain, counter-clockwise.
  std::sort(points.begin(), points.end(),
            [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t start = hull.size();
    for (const Eigen::Vector2d& q : points) {
      while (hull.size() >= start + 2 && cross(hull[hull.size() - 2], hull.back(), q) <= 0) hull.pop_back();
      hull.push_back(q);
    }
    hull.pop_back();
    std::reverse(points.begin(), points.end());
  }
  if (hull.empty()) hull = points;
  bool inside = hull.size() >= 3;
  double d = 1e300;
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Eigen::Vector2d& a = hull[k];
    const Eigen::Vector2d& b = hull[(k + 1) % hull.size()];
    inside = inside && cross(a, b, p) >= 0;
    Eigen::Vector2d q;
    const double dk = segment_distance(p, a, b, &q);
    if (dk < d) d = dk, *nearest = q;
  }
  if (inside) *nearest = p;
  return inside ? 0.0 : d;
}

}  // namespace

FloorSupport floor_support(const Motion& motion, const Body& body, const MotionPlacement& place, double band_m) {
  const int T = motion.size();
  FloorSupport out;
  out.contact.assign(std::size_t(T), false);
  out.frames.resize(std::size_t(T));
  const SoleRows rows(body.sole());
  for (int t = 0; t < T; ++t) {
    Pose p = motion.frames[std::size_t(t)];
    lift_feet(p, place.foot_lift);
    const double floor = place.floor.empty() ? 0.0 : place.floor[std::size_t(t)];
    const PosedBody pb = pose_body(body, p);
    SupportFrame& f = out.frames[std::size_t(t)];
    // Some surface within the band: a foot, or an end of a segment's capsule.
    bool contact = false;
    for (int s = 0; s < 2; ++s) {
      const auto& foot = s ? pb.right_foot : pb.left_foot;
      f.foot_down[std::size_t(s)] = foot_below(body.sole(), rows, foot, floor, band_m);
      const auto ends = foot_ends(p, s);
      f.heel[std::size_t(s)] = ends[0].head<2>(), f.tip[std::size_t(s)] = ends[1].head<2>();
      contact = contact || f.foot_down[std::size_t(s)];
    }
    for (int s = 0; s < kSegmentCount; ++s) {
      const SegmentShape& seg = body.segments()[std::size_t(s)];
      if (!seg.touches_ground) continue;
      const double za = pb.a[s].z() - seg.radius_a_m - floor, zb = pb.b[s].z() - seg.radius_b_m - floor;
      if (za < band_m) f.other.push_back(pb.a[s].head<2>());
      if (zb < band_m) f.other.push_back(pb.b[s].head<2>());
      contact = contact || za < band_m || zb < band_m;
    }
    const Eigen::Vector3d hips = 0.5 * (p[kLeftHip] + p[kRightHip]);
    f.seat = hips.head<2>();
    f.seat_possible = hips.z() - floor < kSeatHipHeight * body.height_m();
    out.contact[std::size_t(t)] = contact;
  }
  return out;
}

std::vector<double> seat_share(const FloorSupport& support, std::vector<Eigen::Vector2d>& zmp, double foot_width_m,
                               double fps) {
  const std::size_t T = support.frames.size();
  std::vector<double> share(T, 1.0);
  std::vector<Eigen::Vector2d> nearest(T, Eigen::Vector2d::Zero());
  std::vector<bool> off(T, false);
  for (std::size_t t = 0; t < T; ++t) {
    const SupportFrame& f = support.frames[t];
    std::vector<Eigen::Vector2d> points = f.other;  // every surface on the floor supports
    for (int s = 0; s < 2; ++s)
      if (f.foot_down[std::size_t(s)]) points.push_back(f.heel[std::size_t(s)]), points.push_back(f.tip[std::size_t(s)]);
    const double d = points.empty() ? 1e300 : hull_distance(zmp[t], points, &nearest[t]) - 0.5 * foot_width_m;
    off[t] = f.seat_possible && d < 1e299 && d > kOffSupportM;
  }
  const std::size_t min_run = std::size_t(std::max(1.0, std::round(kCarriedMinS * fps)));
  for (std::size_t a = 0; a < T;) {
    std::size_t b = a;
    while (b < T && off[b]) ++b;
    if (b - a >= min_run)
      for (std::size_t t = a; t < b; ++t) {
        // Two supports, the seat under the hips and the feet: the feet carry
        // the share of the load that balances its moment about the seat.
        const Eigen::Vector2d seat = support.frames[t].seat, to_feet = nearest[t] - seat;
        share[t] = to_feet.squaredNorm() > 1e-6 ? std::clamp((zmp[t] - seat).dot(to_feet) / to_feet.squaredNorm(), 0.0, 1.0) : 1.0;
        zmp[t] = nearest[t];  // the feet's own load: no moment to balance beyond their support
      }
    a = std::max(b, a + 1);
  }
  return gaussian_smooth(share, kShareSmoothS * fps);
}

double carried_fraction(const Motion& motion, const Body& body, const SimOptions& options, const FloorSupport& support) {
  ComTrack com = com_track(motion, body, options.com_filter_hz, &support.contact);
  const std::vector<double> share = seat_share(support, com.zmp, body.sole().width_m, motion.fps > 0 ? motion.fps : 30);
  int carried = 0;
  for (double s : share) carried += s < kCarriedShare;
  return share.empty() ? 0.0 : double(carried) / double(share.size());
}

}  // namespace ptnet::detail
