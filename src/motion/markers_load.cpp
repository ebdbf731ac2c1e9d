// motion_from_trc: a marker recording -> the canonical joints. Steps: choose
// and resolve the map; check the unit; take the map's markers as tracks and
// fill short gaps; the static trial (read once) rebuilds the landmarks the
// trial lacks; long gaps rebuilt on the segment's markers; the stature; the
// joints per frame; resample; ground; remove a treadmill belt.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <tuple>

#include "markers_internal.hpp"
#include "motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

using V = Eigen::Vector3d;
using detail::PreparedTrial;
using detail::ResolvedMap;

constexpr Range kPlausibleStatureM{1.0, 2.3};  // outside: a warning

std::string markers_found(const Trc& trc) { return detail::bounded_list(trc.markers, 600); }

struct ChosenMap {
  MarkerMap map;
  ResolvedMap r;
};

ChosenMap named_map(const Trc& trc, const std::string& wanted) {
  ChosenMap c{marker_map(wanted), {}};
  c.r = detail::resolve(c.map, trc.markers);
  if (!c.r.problem.empty()) throw Error::in(trc.source, c.r.problem);
  const auto missing = detail::missing_landmarks(c.r, c.map);
  if (!missing.empty())
    throw Error::in(trc.source, "marker map '" + escaped(c.map.name, 40, false) + "' cannot place the markers: it lacks " +
                                    detail::bounded_list(missing, 800, "; ", 200) + "; the file has " + markers_found(trc));
  return c;
}

// The map of options.marker_map, or the shipped map that places the file and
// finds the most landmarks (ties: the one naming more of them as the file
// spells them: the lab's own set before the common vocabulary).
ChosenMap choose_map(const Trc& trc, const std::string& wanted) {
  if (!wanted.empty()) return named_map(trc, wanted);
  std::optional<ChosenMap> best, closest;
  std::vector<std::string> closest_missing;
  std::string problem;
  for (const std::string& name : marker_map_names()) {
    ChosenMap c{marker_map(name), {}};
    c.r = detail::resolve(c.map, trc.markers);
    const auto missing = detail::missing_landmarks(c.r, c.map);
    const auto score = std::make_tuple(c.r.found, c.r.exact);
    if (missing.empty() && !c.r.problem.empty() && problem.empty()) problem = c.r.problem;
    if (missing.empty() && c.r.problem.empty()) {
      if (!best || score > std::make_tuple(best->r.found, best->r.exact)) best = std::move(c);
    } else if (!closest || score > std::make_tuple(closest->r.found, closest->r.exact)) {
      closest_missing = missing;
      closest = std::move(c);
    }
  }
  if (best) return std::move(*best);
  if (!problem.empty()) throw Error::in(trc.source, problem);
  throw Error::in(trc.source, "no shipped marker map (" + join(marker_map_names(), ", ") +
                                  ") places the markers (closest, " + closest->map.name + ", lacks " +
                                  detail::bounded_list(closest_missing, 800, "; ", 200) + "); the file has " +
                                  markers_found(trc) + "; describe them with a map file (docs/markers.md)");
}

// The metres per unit options give (0: the file's Units).
double given_metres_per_unit(const MotionOptions& o) {
  if (o.metres_per_unit > 0) return o.metres_per_unit;
  return o.units == Units::automatic ? 0 : unit_metres(o.units);
}

// A landmark's gaps longer than max_gap_s, rebuilt in each frame on the other
// markers of its segment as they stood in the frame before or after the gap.
// Returns the samples rebuilt; Error where too few of them are there.
int rebuild_long_gaps(PreparedTrial& p, double max_gap_s) {
  detail::Tracks& t = p.t;
  int rebuilt = 0;
  for (int lm = 0; lm < detail::kLandmarkCount; ++lm) {
    const int u = p.m.landmark[std::size_t(lm)];
    if (u < 0) continue;
    for (const detail::Gap& g : p.long_gaps[std::size_t(u)]) {
      std::vector<detail::Cluster> clusters;
      for (const detail::Segment& s : detail::segment_tracks(lm, p.m))
        for (int ref : {g.begin - 1, g.end}) {
          if (ref < 0 || ref >= t.frames || !t.has(ref, u)) continue;
          detail::Cluster c{s.name, {}, {}, t.at(ref, u).cast<double>()};
          for (int k : s.tracks)
            if (k != u) c.members.push_back(k), c.ref.push_back(t.at(ref, k).cast<double>());
          clusters.push_back(std::move(c));
        }
      std::vector<int> unplaced;
      for (int f = g.begin; f < g.end; ++f) {
        const V at = detail::rebuild(t, f, clusters);
        if (std::isfinite(at.x())) t.at(f, u) = at.cast<float>(), ++rebuilt;
        else unplaced.push_back(f);
      }
      if (!unplaced.empty()) detail::throw_unplaced(p, lm, t.names[std::size_t(u)], unplaced, clusters, max_gap_s);
    }
  }
  return rebuilt;
}

// The required landmarks a marker with no sample left out.
void check_required(const PreparedTrial& p, const ResolvedMap& r, const Trc& trc) {
  ResolvedMap now = r;
  for (int k = 0; k < detail::kLandmarkCount; ++k)
    if (p.m.landmark[std::size_t(k)] < 0 && r.marker[std::size_t(k)] >= 0) now.marker[std::size_t(k)] = -1;
  if (detail::missing_landmarks(now, MarkerMap{}).empty()) return;
  for (int k = 0; k < detail::kLandmarkCount; ++k)
    if (now.marker[std::size_t(k)] != r.marker[std::size_t(k)]) {
      ResolvedMap one = r;
      one.marker[std::size_t(k)] = -1;
      if (!detail::missing_landmarks(one, MarkerMap{}).empty())
        throw Error::in(p.source, "marker " + escaped(trc.markers[std::size_t(r.marker[std::size_t(k)])]) + " (" +
                                      detail::landmark_name(k) + ") has no samples");
    }
  throw Error::in(p.source, "the markers with samples do not place the pelvis and both feet");
}

void fill_report(MarkerReport& report, const PreparedTrial& p, const MarkerMap& map, const std::vector<std::string>& rebuilt) {
  report.map = map.name;
  report.placed.clear();
  report.placed_by.clear();
  for (int k = 0; k < detail::kLandmarkCount; ++k) {
    const int u = p.m.landmark[std::size_t(k)];
    if (u < 0) continue;
    report.placed.push_back(detail::landmark_name(k));
    const bool from_static = std::any_of(rebuilt.begin(), rebuilt.end(), [&](const std::string& s) {
      return s.rfind(detail::landmark_name(k) + " ", 0) == 0;
    });
    report.placed_by.push_back(p.t.names[std::size_t(u)] + (from_static ? " (static trial)" : ""));
  }
  report.calibrated = rebuilt;
  report.gap_filled_frames = p.filled;
  report.up_axis = p.up;
  report.metres_per_unit = p.metres_per_unit;
}

// The joints of every frame, at the trial's rate.
Motion joints(const PreparedTrial& p, double h, const std::array<double, 2>& pitch, std::vector<std::string>& methods) {
  Motion m;
  m.name = std::filesystem::path(p.source).stem().string();
  m.fps = p.t.rate_hz;
  m.start_s = p.start_s;
  m.frames.reserve(std::size_t(p.t.frames));
  for (int f = 0; f < p.t.frames; ++f) {
    m.frames.push_back(detail::joints_from_landmarks(detail::landmarks_at(p.t, p.m, f), h, f == 0 ? &methods : nullptr));
    pitch_feet(m.frames.back(), pitch);
  }
  return m;
}

Motion from_trc(const Trc& trc, Trc* owned, const MotionOptions& options, MarkerReport* report) {
  if (!(options.fps > 0 && same_rate(trc.rate_hz, options.fps))) detail::check_read_fps(options);
  if (trc.frames() < 2) throw Error::in(trc.source, "expected at least 2 frames, found " + std::to_string(trc.frames()));
  check_range("max_gap_s", options.max_gap_s, Range{0, 10});
  const ChosenMap chosen = choose_map(trc, options.marker_map);
  const double given = given_metres_per_unit(options);
  PreparedTrial p = detail::prepare_trial(trc, chosen.r, detail::trial_scale(trc, chosen.r, given, 0), options.max_gap_s);
  detail::drop_empty_tracks(p);
  std::optional<detail::StaticTrial> st;
  std::vector<std::string> rebuilt;
  if (!options.static_markers.empty()) {
    st = detail::read_static_trial(options.static_markers, chosen.map, p, given, options.max_gap_s);
    rebuilt = detail::calibrate(p, *st, options.max_gap_s);
  }
  check_required(p, chosen.r, trc);
  if (owned) *owned = Trc{};  // the samples no step needs any more
  const int rebuilt_samples = rebuild_long_gaps(p, options.max_gap_s);
  const double h = st ? st->stature_m : detail::stature_from_legs(p.t, p.m);
  std::vector<std::string> methods;
  Motion m = joints(p, std::clamp(h, 0.5, 2.5), st ? st->foot_pitch : std::array<double, 2>{0, 0}, methods);
  if (st)
    methods.push_back("toe joints: pitched to the canonical flat foot of the static trial (left " +
                      fixed_text(st->foot_pitch[0] * 180 / M_PI, 1) + ", right " +
                      fixed_text(st->foot_pitch[1] * 180 / M_PI, 1) + " degrees)");
  if (options.fps > 0 && !same_rate(m.fps, options.fps)) m = detail::resample_linear(m, options.fps);
  if (options.fps > 0) m.fps = options.fps;
  detail::ground(m);
  const Eigen::Vector2d belt = treadmill_belt_velocity(m);  // reported, removed or not
  if (options.remove_belt && belt.norm() > 0) m = without_belt(std::move(m), belt);
  if (report) {
    fill_report(*report, p, chosen.map, rebuilt);
    report->methods = methods;
    report->rebuilt_samples = rebuilt_samples;
    report->stature_m = std::clamp(h, 0.5, 2.5);
    report->stature_from = st ? "the static trial (median hip height standing)"
                              : "the frames where the subject stands tallest (hip-heel distance, 95th percentile)";
    report->upper_body_assumed = !detail::has_trunk(chosen.r);
    report->warnings.clear();
    if (report->upper_body_assumed)
      report->warnings.push_back("no trunk marker (acromion, C7, clavicle, sternum): the upper body is assumed, "
                                 "upright above the pelvis with the arms hanging (docs/markers.md)");
    if (!kPlausibleStatureM.contains(h))
      report->warnings.push_back("the estimated stature, " + fixed_text(h, 2) + " m, is outside " +
                                 kPlausibleStatureM.text() + " m");
    report->belt_speed_mps = belt.norm();
    report->belt_velocity_mps = belt;
  }
  return m;
}

}  // namespace

Motion motion_from_trc(const Trc& trc, const MotionOptions& options, MarkerReport* report) {
  return from_trc(trc, nullptr, options, report);
}

Motion motion_from_trc(Trc&& trc, const MotionOptions& options, MarkerReport* report) {
  Trc own = std::move(trc);
  return from_trc(own, &own, options, report);
}

}  // namespace ptnet
