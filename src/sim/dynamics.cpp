// Motions that cannot carry their own dynamics: a pelvis whose height the
// rig never moves while the feet step, and frames where the body is held up
// by something that is not the floor.
#include <algorithm>
#include <cmath>

#include "core/anthropometry.hpp"
#include "ptnet/error.hpp"
#include "sim_internal.hpp"

namespace ptnet {

namespace {
constexpr double kMaxFlightS = 0.6;  // s: a longer time off the floor is not a human flight (0.44 m jump)
constexpr double kTooShortS = 0.15;  // s: a shorter one is not told from a flight
}  // namespace

MotionDynamics check_dynamics(const Motion& motion, const SimOptions& options, const MotionPlacement* placed) {
  MotionDynamics d;
  const int T = motion.size();
  if (T == 0) throw Error("check_dynamics: motion '" + motion.name + "' has no frames");
  d.frozen_pelvis = detail::frozen_pelvis_fraction(motion);
  const double ratio = retarget_scale(motion, kFloorReferenceHeightCm);
  const MotionPlacement place = (placed ? *placed : place_motion(motion, options)).scaled(ratio);
  const Motion copy = detail::pitch_corrected(retarget(motion, kFloorReferenceHeightCm), place.foot_pitch);
  const detail::FloorSupport support = detail::floor_support(copy, detail::reference_body(), place, options.compliance_m);
  const std::vector<bool>& on_floor = support.contact;
  d.carried = detail::carried_fraction(copy, detail::reference_body(), options, support);
  // A stretch without contact is a flight when the centre of mass falls
  // through it (its mean vertical acceleration inside is below -g / 2) and
  // it is no longer than a human flight; otherwise the body is held up by
  // something else. Stretches of 0.15 s or less are too short to tell (their
  // acceleration is that of the take-off and the landing as much as of the flight).
  std::vector<double> z;
  for (const Pose& p : copy.frames) z.push_back(centre_of_mass(detail::reference_body(), p).z());
  const double g = anthropometry::kGravity, fps = copy.fps;
  int unsupported = 0;
  for (int a = 0; a < T;) {
    if (on_floor[std::size_t(a)]) {
      ++a;
      continue;
    }
    int b = a;
    while (b < T && !on_floor[std::size_t(b)]) ++b;  // no contact in [a, b)
    const double span = (b - a) / fps;
    bool flight = span <= kTooShortS;
    if (!flight) {  // the velocity change over [a, b - 1], central differences inside
      const auto v = [&](int t) { return (z[std::size_t(t + 1)] - z[std::size_t(t - 1)]) * fps / 2; };
      const int t0 = std::max(a, 1), t1 = std::min(b - 1, T - 2);
      flight = t1 > t0 && (v(t1) - v(t0)) / ((t1 - t0) / fps) < -0.5 * g;
    }
    if (span > kMaxFlightS || !flight) unsupported += b - a;
    a = b;
  }
  d.unsupported = double(unsupported) / T;
  return d;
}

std::vector<std::string> dynamics_warnings(const std::string& name, const MotionDynamics& d) {
  std::vector<std::string> out;
  const auto percent = [](double f) { return std::to_string(int(std::lround(100 * f))) + " %"; };
  if (d.frozen_pelvis > 0)
    out.push_back(name + ": the pelvis height is fixed while the feet step in " + percent(d.frozen_pelvis) +
                  " of frames: its load cannot bounce or fall to zero in flight (it stays near body weight)");
  if (d.unsupported >= 0.05)
    out.push_back(name + ": " + percent(d.unsupported) +
                  " of frames have no body surface on the floor while the body is carried: it stands on "
                  "something that is not the floor, and those frames read no load");
  if (d.carried >= 0.05)
    out.push_back(name + ": in " + percent(d.carried) +
                  " of frames the centre of mass stays off the feet without falling: a seat carries part of the "
                  "body; the feet carry what balances it about the hips, the seat's share is not on the mat");
  return out;
}

}  // namespace ptnet
