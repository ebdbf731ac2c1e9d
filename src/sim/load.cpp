// Total vertical ground reaction force from the centre-of-mass motion:
// F = m (g + a_z) (Newton's second law on the whole body; Winter, Biomechanics
// and Motor Control of Human Movement, ch. 5), and where it acts: the zero-
// moment point of the segments' masses, sum m_i (x_i (g + z''_i) - z_i x''_i)
// / sum m_i (g + z''_i) (the balance of moments about the ground;
// Vukobratovic & Borovac 2004), neglecting the segments' spin about their
// own centres.
#include <algorithm>
#include <cmath>

#include "core/anthropometry.hpp"
#include "core/smooth.hpp"
#include "sim_internal.hpp"

namespace ptnet {
namespace {

constexpr double kLandingHzFactor = 1.5;   // the cutoff around a landing, x com_filter_hz
constexpr double kMinFlightS = 0.08;       // s: off the floor at least this long before a touch-down
constexpr double kLandingBeforeS = 0.05;   // s: the landing window from before the touch-down
constexpr double kLandingAfterS = 0.05;    // s: ... to after it (the impact)
constexpr double kLandingTaperS = 0.05;    // s: raised-cosine ramps either side of the window

// Retargeting's height correction of frame t (Motion::support_shift_m), which
// is no motion of the body: the load's dynamics leave it out.
double support_shift(const Motion& motion, int t) {
  return motion.support_shift_m.empty() ? 0.0 : motion.support_shift_m[std::size_t(t)];
}

// Second differences of x, [T] (ends copied), low-passed: -3 dB at hz for
// a Gaussian of sigma = sqrt(ln 2) / (2 pi hz).
std::vector<double> acceleration(const std::vector<double>& x, double fps, double hz) {
  const int T = int(x.size());
  std::vector<double> a(x.size(), 0.0);
  for (int t = 1; t + 1 < T; ++t) a[t] = (x[t + 1] - 2 * x[t] + x[t - 1]) * fps * fps;
  if (T >= 3) {
    a[0] = a[1];
    a[T - 1] = a[T - 2];
  }
  if (hz > 0) a = gaussian_smooth(a, std::sqrt(std::log(2.0)) / (2 * M_PI * hz) * fps);
  return a;
}

// Per frame, how much of the landing cutoff the vertical acceleration takes
// (0..1, [T]): 1 from kLandingBeforeS before a touch-down that ends a
// flight (kMinFlightS or more without contact) to kLandingAfterS after it,
// raised-cosine ramps of kLandingTaperS either side, 0 elsewhere.
std::vector<double> landing_weight(const std::vector<bool>& contact, double fps) {
  const int T = int(contact.size());
  std::vector<double> w(contact.size(), 0.0);
  const int min_flight = std::max(1, int(std::lround(kMinFlightS * fps)));
  const double taper = kLandingTaperS * fps;
  for (int t = 1, off = contact[0] ? 0 : 1; t < T; ++t) {
    if (!contact[std::size_t(t)]) {
      ++off;
      continue;
    }
    if (off >= min_flight) {
      const double lo = t - kLandingBeforeS * fps, hi = t + kLandingAfterS * fps;
      for (int k = std::max(0, int(lo - taper)); k < std::min(T, int(hi + taper) + 1); ++k) {
        const double d = k < lo ? (lo - k) / taper : (k > hi ? (k - hi) / taper : 0.0);
        if (d < 1) w[std::size_t(k)] = std::max(w[std::size_t(k)], 0.5 + 0.5 * std::cos(M_PI * d));
      }
    }
    off = 0;
  }
  return w;
}

// The zero-moment point of the segments' masses, each at its own centre
// (world x, y; m, [T]): sum m_i (x_i (g + z''_i) - z_i x''_i) / sum m_i (g +
// z''_i), which keeps what the whole-body formula neglects: the angular
// momentum of the segments' motion about the centre of mass (a swinging leg,
// the arms). Accelerations low-passed at hz; beyond 1 g horizontally and
// 5 g vertically they are capture glitches (clamped); with (almost) no load
// the point is meaningless: the centre of mass's projection.
std::vector<Eigen::Vector2d> segment_zmp(const Motion& motion, const Body& body, double fps, double hz) {
  const int T = motion.size();
  const double g = anthropometry::kGravity;
  std::vector<Eigen::Vector2d> num(std::size_t(T), Eigen::Vector2d::Zero()), com(std::size_t(T), Eigen::Vector2d::Zero());
  std::vector<double> den(std::size_t(T), 0.0);
  std::array<std::array<std::vector<double>, 3>, kSegmentCount> c;  // [segment][axis][T]
  for (int t = 0; t < T; ++t) {
    const PosedBody pb = pose_body(body, motion.frames[std::size_t(t)]);
    for (int s = 0; s < kSegmentCount; ++s)
      for (int k = 0; k < 3; ++k)
        c[std::size_t(s)][std::size_t(k)].push_back(0.5 * (pb.a[s][k] + pb.b[s][k]) - (k == 2 ? support_shift(motion, t) : 0.0));
  }
  for (int s = 0; s < kSegmentCount; ++s) {
    const auto& p = c[std::size_t(s)];
    const double m = body.segments()[std::size_t(s)].mass_kg;
    const std::vector<double> ax = acceleration(p[0], fps, hz), ay = acceleration(p[1], fps, hz),
                              az = acceleration(p[2], fps, hz);
    for (std::size_t t = 0; t < std::size_t(T); ++t) {
      const double gz = g + std::clamp(az[t], -g, 4 * g);
      const Eigen::Vector2d ah(std::clamp(ax[t], -g, g), std::clamp(ay[t], -g, g));
      num[t] += m * (Eigen::Vector2d(p[0][t], p[1][t]) * gz - p[2][t] * ah);
      com[t] += m * Eigen::Vector2d(p[0][t], p[1][t]);
      den[t] += m * gz;
    }
  }
  std::vector<Eigen::Vector2d> zmp(static_cast<std::size_t>(T));
  for (std::size_t t = 0; t < std::size_t(T); ++t)
    zmp[t] = den[t] > 0.2 * g * body.mass_kg() ? Eigen::Vector2d(num[t] / den[t]) : Eigen::Vector2d(com[t] / body.mass_kg());
  return zmp;
}

}  // namespace

namespace detail {

ComTrack com_track(const Motion& motion, const Body& body, double com_filter_hz, const std::vector<bool>* contact) {
  const int T = motion.size();
  const double g = anthropometry::kGravity;
  const double fps = motion.fps > 0 ? motion.fps : 30;
  std::vector<double> z(T);
  for (int t = 0; t < T; ++t) z[t] = centre_of_mass(body, motion.frames[t]).z() - support_shift(motion, t);
  const std::vector<double> az0 = acceleration(z, fps, com_filter_hz);
  // Around a landing the vertical acceleration is filtered at a higher
  // cutoff: a touch-down after a flight is a step from free fall to the
  // impact, whose peak comes 30-50 ms after it (drop jumps, running); 4 Hz
  // spreads it over ~0.2 s, a lower, later peak with its leading edge cut
  // off by the flight.
  std::vector<double> az = az0;
  if (contact && com_filter_hz > 0) {
    const std::vector<double> w = landing_weight(*contact, fps);
    const std::vector<double> fast = acceleration(z, fps, kLandingHzFactor * com_filter_hz);
    for (int t = 0; t < T; ++t) az[std::size_t(t)] += w[std::size_t(t)] * (fast[std::size_t(t)] - az0[std::size_t(t)]);
  }
  ComTrack out;
  out.load_n.resize(T);
  for (int t = 0; t < T; ++t)  // clamped at 0 (the ground only pushes) and at 5 g (capture glitches)
    out.load_n[t] = body.mass_kg() * (g + std::clamp(az[t], -g, 4 * g));
  out.zmp = segment_zmp(motion, body, fps, com_filter_hz);
  return out;
}

}  // namespace detail

}  // namespace ptnet
