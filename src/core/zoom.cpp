// Body-scale zoom of pressure maps about the mat centre (pressure.hpp).
#include <cmath>

#include "ptnet/error.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

void zoom_frames(const float* in, float* out, int frames, int rows, int cols, double scale, double gain) {
  if (!(scale > 0) || !std::isfinite(scale))
    throw Error("zoom: scale: expected a finite number > 0, found " + number_text(scale));
  if (!(gain >= 0) || !std::isfinite(gain))  // a pressure gain: negative would give negative pressure
    throw Error("zoom: gain: expected a finite number >= 0, found " + number_text(gain));
  // Output cell (r, c) samples the input at centre + (r - centre) / scale, in
  // cell-centre coordinates; bilinear weights per row and column, precomputed.
  const double cr = 0.5 * (rows - 1), cc = 0.5 * (cols - 1);
  struct Tap { int i0 = 0; float w0 = 0, w1 = 0; };  // samples i0 (w0) and i0 + 1 (w1)
  auto taps = [&](int n, double centre) {
    std::vector<Tap> t(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double x = centre + (i - centre) / scale;
      const int i0 = int(std::floor(x));
      const double f = x - i0;
      Tap& tap = t[std::size_t(i)];
      tap.i0 = i0;
      tap.w0 = (i0 >= 0 && i0 < n) ? float(1 - f) : 0.0f;
      tap.w1 = (i0 + 1 >= 0 && i0 + 1 < n) ? float(f) : 0.0f;
    }
    return t;
  };
  const auto tr = taps(rows, cr), tc = taps(cols, cc);
  const std::size_t cells = std::size_t(rows) * std::size_t(cols);
  const float g = float(gain);
  for (int t = 0; t < frames; ++t) {
    const float* f = in + std::size_t(t) * cells;
    float* o = out + std::size_t(t) * cells;
    for (int r = 0; r < rows; ++r) {
      const Tap& a = tr[std::size_t(r)];
      for (int c = 0; c < cols; ++c) {
        const Tap& b = tc[std::size_t(c)];
        auto at = [&](int i, int j) { return f[std::size_t(i) * std::size_t(cols) + std::size_t(j)]; };
        float v = 0;
        if (a.w0 > 0) {
          if (b.w0 > 0) v += a.w0 * b.w0 * at(a.i0, b.i0);
          if (b.w1 > 0) v += a.w0 * b.w1 * at(a.i0, b.i0 + 1);
        }
        if (a.w1 > 0) {
          if (b.w0 > 0) v += a.w1 * b.w0 * at(a.i0 + 1, b.i0);
          if (b.w1 > 0) v += a.w1 * b.w1 * at(a.i0 + 1, b.i0 + 1);
        }
        o[std::size_t(r) * std::size_t(cols) + std::size_t(c)] = g * v;
      }
    }
  }
}

PressureSequence zoom_about_centre(const PressureSequence& in, double scale, double gain) {
  PressureSequence out(in.mat, in.frames(), in.fps);
  zoom_frames(in.kpa.data(), out.kpa.data(), in.frames(), in.mat.rows, in.mat.cols, scale, gain);
  return out;
}

}  // namespace ptnet
