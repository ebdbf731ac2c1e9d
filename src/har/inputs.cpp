// Classifier inputs (ptnet/har.hpp): windows block-averaged over time and
// space, log1p(kPa).
//
// Dimension legend: T frames, H x W cells, B = time_blocks, P = pool.
#include <algorithm>
#include <cmath>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {

void PreparedWindows::append(const PreparedWindows& other) {
  if (other.values.empty()) return;
  if (values.empty() && channels == 0) {
    *this = other;
    return;
  }
  if (other.channels != channels || other.rows != rows || other.cols != cols)
    throw Error("har: cannot join windows of shape " + std::to_string(other.channels) + "x" +
                std::to_string(other.rows) + "x" + std::to_string(other.cols) + " to " +
                std::to_string(channels) + "x" + std::to_string(rows) + "x" + std::to_string(cols));
  values.insert(values.end(), other.values.begin(), other.values.end());
}

// window [T, H, W] kPa -> appends [B, H / P, W / P] log1p(kPa) to out.
void prepare_window(const float* window, int frames, const MatSpec& mat,
                    const InputOptions& options, PreparedWindows& out) {
  const int blocks = options.time_blocks, pool = options.pool;
  if (blocks < 1 || blocks > frames)
    throw Error("har: time blocks must be in 1.." + std::to_string(frames) + ", found " +
                std::to_string(blocks));
  if (pool < 1 || pool > mat.rows || pool > mat.cols)
    throw Error("har: pool must be in 1.." + std::to_string(std::min(mat.rows, mat.cols)) +
                ", found " + std::to_string(pool));
  const int rows = mat.rows / pool, cols = mat.cols / pool;
  if (out.channels == 0 && out.values.empty()) {
    out.channels = blocks;
    out.rows = rows;
    out.cols = cols;
  } else if (out.channels != blocks || out.rows != rows || out.cols != cols) {
    throw Error("har: window shape differs from the windows prepared before");
  }
  const std::size_t base = out.values.size();
  out.values.resize(base + std::size_t(blocks) * rows * cols, 0.0f);
  float* dst = out.values.data() + base;
  const int cells = mat.cells();
  for (int b = 0; b < blocks; ++b) {
    const int t0 = b * frames / blocks, t1 = (b + 1) * frames / blocks;
    const double norm = 1.0 / (double(t1 - t0) * pool * pool);
    float* plane = dst + std::size_t(b) * rows * cols;
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        double s = 0;
        for (int t = t0; t < t1; ++t) {
          const float* f = window + std::size_t(t) * cells;
          for (int dr = 0; dr < pool; ++dr)
            for (int dc = 0; dc < pool; ++dc)
              s += std::max(0.0f, f[(r * pool + dr) * mat.cols + c * pool + dc]);
        }
        plane[r * cols + c] = float(std::log1p(s * norm));
      }
  }
}

PreparedWindows prepare_windows(const WindowBatch& windows, const InputOptions& options) {
  PreparedWindows out;
  for (int i = 0; i < windows.count(); ++i)
    prepare_window(windows.window(i), windows.frames, windows.mat, options, out);
  return out;
}

}  // namespace ptnet::har
