// The sensor model of a resistive pressure mat, applied per frame:
// crosstalk blur -> saturation -> read noise -> activation threshold -> ADC
// quantisation (then clamped to [0, saturation]). Only the cells that can
// read above the threshold are visited (and draw noise).
#include <algorithm>
#include <cmath>
#include <cstring>

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
                  std::uint64_t& rng, RowSpan pressed) {
  const int R = mat.rows, C = mat.cols;
  const float k = float(sensor.crosstalk);
  const float sat = float(sensor.saturation_kpa), sd = float(sensor.noise_sd_kpa);
  const float thr = float(sensor.threshold_kpa), q = float(sensor.quantum_kpa);
  // The noise is bounded (|normalish| <= 2 sqrt(3) sd): a cell further below
  // the threshold than that reads 0 whatever the draw, and draws nothing.
  const float reach = 3.4642f * sd;
  const bool sparse = thr > reach;
  // Rows and columns holding any pressure (plus the crosstalk halo). A row
  // is tested at once: v != 0 exactly when its bits other than the sign are
  // not all 0 (NaN included), an OR that vectorises.
  int r0 = R, r1 = -1, c0 = C, c1 = -1;
  for (int r = std::max(0, pressed.first); r <= std::min(R - 1, pressed.last); ++r) {
    const float* row = frame + r * C;
    std::uint32_t any = 0;
    for (int c = 0; c < C; ++c) {
      std::uint32_t bits;
      std::memcpy(&bits, row + c, 4);
      any |= bits & 0x7fffffffu;
    }
    if (!any) continue;
    int first = 0, last = C - 1;
    while (row[first] == 0) ++first;
    while (row[last] == 0) --last;
    r0 = std::min(r0, r), r1 = r;
    c0 = std::min(c0, first), c1 = std::max(c1, last);
  }
  if (r1 < 0 && sparse) return;  // an empty frame stays empty
  if (k > 0 && r1 >= 0) {
    r0 = std::max(0, r0 - 1), r1 = std::min(R - 1, r1 + 1);
    c0 = std::max(0, c0 - 1), c1 = std::min(C - 1, c1 + 1);
    for (int r = r0; r <= r1; ++r) std::copy(frame + r * C + c0, frame + r * C + c1 + 1, scratch + r * C + c0);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const float* s = scratch + r * C + c;
        float nb = 0;
        if (r > r0) nb += s[-C];
        if (r < r1) nb += s[C];
        if (c > c0) nb += s[-1];
        if (c < c1) nb += s[1];
        frame[r * C + c] = (1 - 4 * k) * s[0] + k * nb;
      }
    }
  }
  auto read = [&](float v) {
    v = std::min(v, sat);
    if (sd > 0) v += sd * normalish(rng);
    if (v < thr) return 0.0f;
    if (q > 0) v = float(std::nearbyint(v / q)) * q;
    return std::clamp(v, 0.0f, sat);
  };
  if (sparse) {
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) {
        float& v = frame[r * C + c];
        v = v + reach < thr ? 0.0f : read(v);
      }
  } else {
    for (int i = 0; i < R * C; ++i) frame[i] = read(frame[i]);
  }
}

}  // namespace ptnet::detail
