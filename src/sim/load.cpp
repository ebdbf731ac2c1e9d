// Total vertical ground reaction force from the centre-of-mass motion:
// F = m (g + a_z) (Newton's second law on the whole body; Winter, Biomechanics
// and Motor Control of Human Movement, ch. 5).
#include <algorithm>
#include <cmath>

#include "ptnet/anthropometry.hpp"
#include "sim_internal.hpp"

namespace ptnet {

std::vector<double> vertical_load(const Motion& motion, const Body& body, double com_filter_hz) {
  const int T = motion.size();
  const double g = anthropometry::kGravity;
  std::vector<double> z(T), a(T, 0.0);
  for (int t = 0; t < T; ++t) z[t] = centre_of_mass(body, motion.frames[t]).z();
  const double fps = motion.fps > 0 ? motion.fps : 30;
  for (int t = 1; t + 1 < T; ++t) a[t] = (z[t + 1] - 2 * z[t] + z[t - 1]) * fps * fps;
  if (T >= 3) {
    a[0] = a[1];
    a[T - 1] = a[T - 2];
  }
  // Gaussian low-pass: -3 dB at f_c for sigma = sqrt(ln 2) / (2 pi f_c).
  if (com_filter_hz > 0) a = detail::gaussian_smooth(a, std::sqrt(std::log(2.0)) / (2 * M_PI * com_filter_hz) * fps);
  std::vector<double> f(T);
  for (int t = 0; t < T; ++t) {
    // Clamped at 0 (the ground only pushes) and at 5 g (capture glitches).
    double az = std::clamp(a[t], -g, 4 * g);
    f[t] = body.mass_kg() * (g + az);
  }
  return f;
}

}  // namespace ptnet
