// synthetic_walk: foot-like pressure blobs for tests and benchmarks
// (support/synthetic_walk.hpp).
#include "support/synthetic_walk.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace ptnet {

namespace {
constexpr double kG = 9.81;            // m/s^2
constexpr double kStepPeriodS = 0.55;  // time between successive heel strikes
constexpr double kStanceS = 0.68;      // one foot's contact time (double support overlaps)
constexpr double kNoiseKpa = 0.3;      // sensor noise std
constexpr double kThresholdKpa = 1.0;  // activation threshold

double clamp01(double v) { return std::min(1.0, std::max(0.0, v)); }

// Plantar load shape at foot-local (a along the foot from its centre, l lateral,
// positive outward), in units of the foot length; u = stance phase in [0, 1].
double plantar(double a, double l, double u) {
  auto blob = [](double da, double dl, double sa, double sl) {
    return std::exp(-0.5 * (da * da / (sa * sa) + dl * dl / (sl * sl)));
  };
  const double heel = clamp01(1.0 - 1.6 * u) + 0.15 * clamp01(1.0 - u);
  const double fore = std::sin(M_PI * clamp01(u * 1.15)) * 0.9 + 0.1 * clamp01(u * 3);
  const double toes = clamp01((u - 0.45) * 2.5) * clamp01((1.0 - u) * 5);
  const double mid = 0.25 * std::sin(M_PI * u);
  double p = heel * blob(a + 0.33, l, 0.11, 0.12) + fore * blob(a - 0.2, l + 0.02, 0.1, 0.16) +
             toes * blob(a - 0.42, l - 0.03, 0.06, 0.12) + mid * blob(a, l - 0.1, 0.16, 0.06);
  // Outline of the sole: an ellipse 1 long and 0.38 wide.
  if ((a * a) / 0.25 + (l * l) / (0.19 * 0.19) > 1.0) return 0.0;
  return p;
}
}  // namespace

PressureSequence synthetic_walk(const MatSpec& mat, int frames, double fps, double height_cm,
                                double weight_kg, unsigned long long seed) {
  PressureSequence seq(mat, frames, fps);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, kNoiseKpa);
  const double foot_len = 0.152 * height_cm / 100;  // anthropometry: foot length ~0.152 H
  const double step_len = 0.41 * height_cm / 100;   // step length ~0.41 H at normal speed
  const double half_gait = 0.095 * height_cm / 170;  // lateral offset of each foot
  const double L = mat.rows * mat.pitch_m, W = mat.cols * mat.pitch_m;
  const double x0 = -L / 2 + 0.6 * foot_len;  // first heel strike near the near end
  const int steps = int(std::ceil(frames / fps / kStepPeriodS)) + 2;
  std::vector<double> jitter(steps);
  for (auto& j : jitter) j = std::uniform_real_distribution<double>(-0.02, 0.02)(rng);

  std::vector<double> shape(mat.cells());
  for (int t = 0; t < frames; ++t) {
    const double time = t / fps;
    float* out = seq.frame(t);
    for (int k = 0; k < steps; ++k) {
      const double u = (time - k * kStepPeriodS) / kStanceS;
      if (u < 0 || u > 1) continue;
      const bool left = k % 2 == 0;
      // Passes restart at the near end once the walker has left the mat.
      const int per_pass = std::max(1, int((L - 1.2 * foot_len) / step_len) + 1);
      const double xc = x0 + (k % per_pass) * step_len + jitter[k];
      const double yc = (left ? 1 : -1) * half_gait;
      // Vertical load: double-hump over stance, shared with the other foot.
      const double load = weight_kg * kG * (0.55 * std::sin(M_PI * u) + 0.45 * std::pow(std::sin(M_PI * u), 6) * 1.1);
      double sum = 0;
      for (int r = 0; r < mat.rows; ++r) {
        const double x = L / 2 - (r + 0.5) * mat.pitch_m;
        for (int c = 0; c < mat.cols; ++c) {
          const double y = W / 2 - (c + 0.5) * mat.pitch_m;
          const double a = (x - xc) / foot_len;
          const double l = (y - yc) / foot_len * (left ? 1 : -1);
          double v = std::abs(a) < 0.6 ? plantar(a, l, u) : 0.0;
          shape[r * mat.cols + c] = v;
          sum += v;
        }
      }
      if (sum <= 0) continue;
      const double scale = load / (sum * mat.cell_area_m2()) / 1000.0;  // Pa -> kPa
      for (int i = 0; i < mat.cells(); ++i) out[i] += float(shape[i] * scale);
    }
    for (int i = 0; i < mat.cells(); ++i) {
      if (out[i] <= 0) continue;
      double v = out[i] + noise(rng);
      out[i] = v < kThresholdKpa ? 0.0f : float(v);
    }
  }
  return seq;
}

}  // namespace ptnet
