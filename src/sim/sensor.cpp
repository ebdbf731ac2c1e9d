// The sensor model of a resistive pressure mat, applied per frame:
// crosstalk blur -> saturation -> read noise -> activation threshold -> ADC
// quantisation (then clamped to [0, saturation]).
#include <algorithm>
#include <cmath>

#include "sim_internal.hpp"

namespace ptnet::detail {
namespace {

// splitmix64: a tiny, well-mixed generator with a fixed output on every platform.
inline std::uint64_t next(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Approximately standard normal: the sum of four 16-bit uniforms (Irwin-Hall,
// variance 1/3 per unit range), centred and scaled. One draw per cell.
inline float normalish(std::uint64_t& state) {
  std::uint64_t x = next(state);
  double s = double(x & 0xffff) + double((x >> 16) & 0xffff) + double((x >> 32) & 0xffff) +
             double(x >> 48);
  return float((s / 65536.0 - 2.0) * 1.7320508075688772);
}

}  // namespace

void apply_sensor(const SensorModel& sensor, const MatSpec& mat, float* frame, float* scratch,
                  std::uint64_t& rng) {
  const int R = mat.rows, C = mat.cols;
  const float k = float(sensor.crosstalk);
  if (k > 0) {
    std::copy(frame, frame + R * C, scratch);
    for (int r = 0; r < R; ++r) {
      for (int c = 0; c < C; ++c) {
        const float* s = scratch + r * C + c;
        float nb = 0;
        if (r > 0) nb += s[-C];
        if (r + 1 < R) nb += s[C];
        if (c > 0) nb += s[-1];
        if (c + 1 < C) nb += s[1];
        frame[r * C + c] = (1 - 4 * k) * s[0] + k * nb;
      }
    }
  }
  const float sat = float(sensor.saturation_kpa), sd = float(sensor.noise_sd_kpa);
  const float thr = float(sensor.threshold_kpa), q = float(sensor.quantum_kpa);
  for (int i = 0; i < R * C; ++i) {
    float v = std::min(frame[i], sat);
    if (sd > 0) v += sd * normalish(rng);
    if (v < thr) v = 0;
    if (q > 0) v = std::round(v / q) * q;
    frame[i] = std::clamp(v, 0.0f, sat);
  }
}

}  // namespace ptnet::detail
