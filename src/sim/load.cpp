// Total vertical ground reaction force from the centre-of-mass motion:
// F = m (g + a_z) (Newton's second law on the whole body; Winter, Biomechanics
// and Motor Control of Human Movement, ch. 5), and where it acts: the zero-
// moment point of the centre of mass, x_com - z_com a_xy / (g + a_z) (the
// inverted-pendulum balance of moments about the ground; Vukobratovic &
// Borovac 2004), neglecting the segments' own angular momentum.
#include <algorithm>
#include <cmath>

#include "core/anthropometry.hpp"
#include "sim_internal.hpp"

namespace ptnet {
namespace {

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
  if (hz > 0) a = detail::gaussian_smooth(a, std::sqrt(std::log(2.0)) / (2 * M_PI * hz) * fps);
  return a;
}

}  // namespace

namespace detail {

ComTrack com_track(const Motion& motion, const Body& body, double com_filter_hz) {
  const int T = motion.size();
  const double g = anthropometry::kGravity;
  const double fps = motion.fps > 0 ? motion.fps : 30;
  std::vector<double> x(T), y(T), z(T);
  for (int t = 0; t < T; ++t) {
    const Eigen::Vector3d c = centre_of_mass(body, motion.frames[t]);
    x[t] = c.x(), y[t] = c.y(), z[t] = c.z();
  }
  // Horizontal: half the cutoff; the zero-moment point only steers the
  // centre of pressure, and capture jitter in a_xy moves it by z / g per m/s^2.
  const std::vector<double> ax = acceleration(x, fps, 0.5 * com_filter_hz),
                            ay = acceleration(y, fps, 0.5 * com_filter_hz), az = acceleration(z, fps, com_filter_hz);
  ComTrack out;
  out.load_n.resize(T);
  out.zmp.resize(T);
  for (int t = 0; t < T; ++t) {
    // Clamped at 0 (the ground only pushes) and at 5 g (capture glitches).
    const double a = std::clamp(az[t], -g, 4 * g);
    out.load_n[t] = body.mass_kg() * (g + a);
    // Horizontal accelerations beyond ~1 g are capture glitches too; with
    // (almost) no load the point is meaningless: keep the CoM's projection.
    const double gz = g + a;
    const Eigen::Vector2d ah(std::clamp(ax[t], -g, g), std::clamp(ay[t], -g, g));
    const double h = std::max(0.0, z[t]);
    out.zmp[t] = Eigen::Vector2d(x[t], y[t]) - (gz > 0.2 * g ? h / gz : 0.0) * ah;
  }
  return out;
}

}  // namespace detail

}  // namespace ptnet
