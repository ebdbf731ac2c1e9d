// Units and up axis: names, and metres per file unit (given or detected).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fk.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

// The CMU "cgspeed" BVH unit: 1/0.45 inch (Hahne's conversion notes).
constexpr double kCmuUnitM = 2.54 / 0.45 / 100;  // 0.056444 m
constexpr double kTypicalHeightM = 1.7;
constexpr double kMinHeightM = 1.0, kMaxHeightM = 2.3;

}  // namespace

double unit_metres(Units u) {
  switch (u) {
    case Units::m:
      return 1.0;
    case Units::cm:
      return 0.01;
    case Units::mm:
      return 0.001;
    case Units::in:
      return 0.0254;
    case Units::cmu:
      return kCmuUnitM;
    case Units::automatic:
      break;
  }
  return 0;
}

namespace {

// Largest extent (file units) of the joints and end sites in frame 0, over
// the three axes: the standing height for an upright first frame, and still
// the body's length when the first frame lies or the rig's rest is z-up.
double first_frame_extent(const Bvh& bvh) {
  const std::size_t J = bvh.joints.size();
  std::vector<Eigen::Vector3d> p(J);
  std::vector<Eigen::Matrix3d> r(J);
  detail::FkLayout(bvh, 1.0).run(bvh.frame(0), p.data(), r.data());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (std::size_t j = 0; j < J; ++j) {
    lo = lo.cwiseMin(p[j]);
    hi = hi.cwiseMax(p[j]);
    if (bvh.joints[j].has_end_site) {
      Eigen::Vector3d e = p[j] + r[j] * bvh.joints[j].end_site;
      lo = lo.cwiseMin(e);
      hi = hi.cwiseMax(e);
    }
  }
  return (hi - lo).maxCoeff();
}

}  // namespace

Units parse_units(const std::string& text) {
  const std::string s = lower(text);
  if (s == "auto" || s == "automatic") return Units::automatic;
  if (s == "m") return Units::m;
  if (s == "cm") return Units::cm;
  if (s == "mm") return Units::mm;
  if (s == "in" || s == "inch") return Units::in;
  if (s == "cmu") return Units::cmu;
  throw Error("units: expected auto, m, cm, mm, in or cmu, found " +
              (text.empty() ? std::string("nothing") : text));
}

UpAxis parse_up_axis(const std::string& text) {
  const std::string s = lower(text);
  if (s == "y") return UpAxis::y;
  if (s == "z") return UpAxis::z;
  throw Error("up axis: expected y or z, found " + (text.empty() ? std::string("nothing") : text));
}

const char* up_axis_name(UpAxis up) { return up == UpAxis::y ? "y" : "z"; }

const char* units_name(Units units) {
  switch (units) {
    case Units::automatic:
      return "auto";
    case Units::m:
      return "m";
    case Units::cm:
      return "cm";
    case Units::mm:
      return "mm";
    case Units::in:
      return "in";
    case Units::cmu:
      return "cmu";
  }
  return "?";
}

double metres_per_unit(const Bvh& bvh, Units units, UpAxis up) {
  if (units != Units::automatic) return unit_metres(units);
  if (bvh.frames() < 1 || bvh.joints.empty())
    throw Error::in(bvh.source, "cannot detect units without a frame; pass " + field_text("units"));
  const double extent = first_frame_extent(bvh);
  if (!(extent > 0) || !std::isfinite(extent))
    throw Error::in(bvh.source, "cannot detect units: the first frame has no extent; pass " +
                                    field_text("units"));
  // The candidate giving a human height (1.0-2.3 m) closest to 1.7 m; if
  // none does, the one closest to 1.7 m by ratio.
  const Units candidates[] = {Units::m, Units::cm, Units::mm, Units::in, Units::cmu};
  Units best = Units::cm;
  double best_score = std::numeric_limits<double>::infinity();
  for (Units u : candidates) {
    const double h = extent * unit_metres(u);
    const bool human = h >= kMinHeightM && h <= kMaxHeightM;
    const double score =
        human ? std::abs(h - kTypicalHeightM) : 1e3 + std::abs(std::log(h / kTypicalHeightM));
    if (score < best_score) {
      best_score = score;
      best = u;
    }
  }
  return unit_metres(best);
}

}  // namespace ptnet
