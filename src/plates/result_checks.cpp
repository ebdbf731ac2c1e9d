// What a trial's figures rest on (ptnet/plates.hpp: check_gait_result): the
// plates on the markers' clock, the ground reaction's sign, some load, some
// frame compared.
#include <algorithm>
#include <cmath>

#include "ptnet/error.hpp"
#include "ptnet/plates.hpp"

namespace ptnet {
namespace {

std::string span_text(double a, double b) { return fixed_text(a, 3) + "-" + fixed_text(b, 3) + " s"; }

// The share of the plates' load (frames above flight_bw) given to a foot,
// their CoP within PhysicsBenchOptions::assign_m of it: ~1 when the plates
// and the markers are in one frame and one unit.
double load_under_feet(const GaitTrialResult& r, const PhysicsBenchOptions& o) {
  double total = 0, feet = 0;
  for (std::size_t t = 0; t < r.time_s.size(); ++t) {
    const double bw = r.plates.total_bw[t];
    if (!(bw > o.flight_bw)) continue;
    total += bw;
    for (double f : r.plates.foot_bw[t])
      if (std::isfinite(f)) feet += f;
  }
  return total > 0 ? feet / total : 1.0;
}

}  // namespace

std::vector<std::string> check_gait_result(const GaitTrialResult& r, const PhysicsBenchOptions& o) {
  const std::size_t T = r.time_s.size();
  const std::string where = r.trial.plates;
  const std::string trial = "trial " + escaped(r.trial.name, 60) + ": ";
  std::size_t covered = 0, below = 0, above = 0, compared = 0, first = T, last = 0;
  double sum_bw = 0;
  for (std::size_t t = 0; t < T; ++t) {
    const double bw = r.plates.total_bw[t];
    if (!std::isfinite(bw)) continue;
    ++covered, sum_bw += bw;
    first = std::min(first, t), last = t;
    below += bw < -o.flight_bw;
    above += bw > o.flight_bw;
    compared += r.compared[t];
  }
  if (T == 0) throw Error::in(where, trial + "no frames simulated: nothing to compare");
  const std::string markers = span_text(r.time_s.front(), r.time_s.back());
  if (covered == 0)
    throw Error::in(where, trial + "no plate sample within the markers' " + markers +
                               ": the plates on another clock? nothing to compare");
  if (below > above)
    throw Error::in(where, trial + "the vertical force is below zero in " +
                               fixed_text(100.0 * double(below) / double(covered), 0) + " % of the frames (mean " +
                               fixed_text(sum_bw / double(covered), 2) +
                               " BW): the force on the plates, not the ground reaction on the feet; negate the "
                               "plates' force columns (vx, vy, vz) and run again");
  if (above == 0)
    throw Error::in(where, trial + "the plates carry no load (above " + number_text(o.flight_bw) + " BW) in any of the " +
                               std::to_string(covered) + " frames they cover: nothing to compare");
  if (const double share = load_under_feet(r, o); share < 0.5)
    throw Error::in(where, trial + "the plates' centres of pressure are within " + number_text(o.assign_m) +
                               " m of a foot for " + fixed_text(100 * share, 0) +
                               " % of their load: the CoP in mm (OpenSim storage has metres), or in another lab "
                               "frame than the markers'? nothing per foot to compare");
  if (compared == 0)
    throw Error::in(where, trial + "no frame compared (the plates see only some steps, and none of the " +
                               std::to_string(T) + " frames whole: coverage)");
  std::vector<std::string> warnings;
  if (covered < T)
    warnings.push_back(trial + "the plates cover " + fixed_text(100.0 * double(covered) / double(T), 0) + " % of the " +
                       std::to_string(T) + " frames (" + span_text(r.time_s[first], r.time_s[last]) +
                       " of the markers' " + markers + "): the figures are over those; the plates on another clock?");
  return warnings;
}

}  // namespace ptnet
