// Checks shared by every reader of pressure frames, a frame's load and
// binary R^2 from counts (ptnet/pressure.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include "ptnet/error.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

FrameLoad frame_load(const float* frame, const MatSpec& mat, double contact_kpa) {
  double sum = 0, sx = 0, sy = 0;
  int contact = 0;
  for (int r = 0; r < mat.rows; ++r)
    for (int c = 0; c < mat.cols; ++c) {
      const double v = std::max(0.0f, frame[r * mat.cols + c]);
      sum += v, sx += v * mat.cell_x(r), sy += v * mat.cell_y(c);
      contact += v > contact_kpa;
    }
  FrameLoad f;
  f.force_n = sum * 1000.0 * mat.cell_area_m2();
  f.contact_m2 = contact * mat.cell_area_m2();
  if (sum > 0) f.x_m = sx / sum, f.y_m = sy / sum;
  return f;
}

double binary_r2_from_counts(double mismatches, double ones, double n) {
  if (n <= 0) return 1;
  if (ones <= 0 || ones >= n) return mismatches == 0 ? 1.0 : 0.0;  // constant truth: SS_tot = 0
  const double q = ones / n;
  return 1.0 - mismatches / (n * q * (1.0 - q));
}

std::size_t first_non_finite(const float* kpa, std::size_t n) {
  constexpr std::size_t kBlock = 1024;
  constexpr std::uint32_t kExponent = 0x7f800000u;  // all ones: Inf or NaN
  for (std::size_t b = 0; b < n; b += kBlock) {
    const std::size_t e = std::min(n, b + kBlock);
    std::uint32_t bad = 0;
    for (std::size_t i = b; i < e; ++i) {
      std::uint32_t bits;
      std::memcpy(&bits, kpa + i, 4);
      bad |= std::uint32_t((bits & kExponent) == kExponent);
    }
    if (bad)
      for (std::size_t i = b; i < e; ++i)
        if (!std::isfinite(kpa[i])) return i;
  }
  return n;
}

void check_finite(const float* kpa, std::size_t n, int cells, const std::string& file, const std::string& what,
                  std::size_t first_frame) {
  const std::size_t i = first_non_finite(kpa, n);
  if (i < n)
    throw Error::in(file, (what.empty() ? std::string() : what + ": ") + "non-finite value (NaN or Inf) in frame " +
                              std::to_string(first_frame + i / std::size_t(cells > 0 ? cells : 1)));
}

void check_pressure(const float* kpa, std::size_t n, int cells, const std::string& file, const std::string& what,
                    std::size_t first_frame) {
  const float lo = float(kPressureRangeKpa.lo), hi = float(kPressureRangeKpa.hi);
  // One vectorised pass: NaN fails both comparisons, infinities the range;
  // the offender is looked for only when there is one.
  unsigned bad = 0;
  std::size_t k = 0;
#if defined(__SSE2__)
  // Four at a time (the compiler does not vectorise the unordered tests).
  const __m128 vlo = _mm_set1_ps(lo), vhi = _mm_set1_ps(hi);
  __m128 out = _mm_setzero_ps();
  for (; k + 4 <= n; k += 4) {
    const __m128 v = _mm_loadu_ps(kpa + k);
    out = _mm_or_ps(out, _mm_or_ps(_mm_cmpnge_ps(v, vlo), _mm_cmpnle_ps(v, vhi)));
  }
  bad = unsigned(_mm_movemask_ps(out));
#endif
  for (; k < n; ++k) bad |= unsigned(!(kpa[k] >= lo)) | unsigned(!(kpa[k] <= hi));
  if (!bad) return;
  check_finite(kpa, n, cells, file, what, first_frame);
  const std::size_t i = std::size_t(std::find_if(kpa, kpa + n, [&](float v) { return v < lo || v > hi; }) - kpa);
  throw Error::in(file, (what.empty() ? std::string() : what + ": ") + number_text(kpa[i]) + " kPa in frame " +
                            std::to_string(first_frame + i / std::size_t(cells > 0 ? cells : 1)) + ", outside " +
                            kPressureRangeKpa.text() + " kPa");
}

}  // namespace ptnet
