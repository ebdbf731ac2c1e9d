// ptnet/pressure.hpp: the pressure-mat geometry and a pressure sequence, the
// type every stage after the simulator exchanges.
//
//   ptnet::PressureSequence seq(ptnet::MatSpec{}, /*frames=*/90, /*fps=*/30);
//   seq.at(t, row, col) = 42.0f;   // kPa
//
// Mat axes: row 0 at the mat's far end (+x end of the long axis), rows grow
// towards the near end; col 0 on the walker's left (+y), cols grow to the
// right. Cell (r, c) covers x in [L/2 - (r+1) p, L/2 - r p] and
// y in [W/2 - (c+1) p, W/2 - c p] around the mat centre (L = rows p,
// W = cols p). See docs/formats.md.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/paper.hpp"

namespace ptnet {

struct MatSpec {
  int rows = kMatRows;          // cells along the long (walking) axis
  int cols = kMatCols;          // cells across
  double pitch_m = kMatPitchM;  // cell size (m)
  int cells() const { return rows * cols; }
  double cell_area_m2() const { return pitch_m * pitch_m; }
  // The centre of cell row r along the mat (x) and of column c across it
  // (y), m, in the mat's frame above.
  double cell_x(int r) const { return rows * pitch_m / 2 - (r + 0.5) * pitch_m; }
  double cell_y(int c) const { return cols * pitch_m / 2 - (c + 0.5) * pitch_m; }
  bool operator==(const MatSpec& o) const {
    return rows == o.rows && cols == o.cols && pitch_m == o.pitch_m;
  }
};

struct PressureSequence {
  MatSpec mat;
  double fps = kFps;
  std::vector<float> kpa;  // [T, rows, cols], kPa, row-major

  PressureSequence() = default;
  PressureSequence(const MatSpec& m, int frames, double rate)
      : mat(m), fps(rate), kpa(std::size_t(frames) * m.cells(), 0.0f) {}
  int frames() const { return mat.cells() ? int(kpa.size() / mat.cells()) : 0; }
  float* frame(int t) { return kpa.data() + std::size_t(t) * mat.cells(); }
  const float* frame(int t) const { return kpa.data() + std::size_t(t) * mat.cells(); }
  float& at(int t, int r, int c) { return frame(t)[r * mat.cols + c]; }
  float at(int t, int r, int c) const { return frame(t)[r * mat.cols + c]; }
};

// An activation threshold: cells below `kpa` set to 0 (a trained model's
// fitted contact threshold, ModelDir::norm.contact_threshold_kpa).
inline void zero_below(PressureSequence& s, double kpa) {
  for (float& v : s.kpa)
    if (v < kpa) v = 0.0f;
}

// What one frame reads, as a force plate under the mat would: the vertical
// force (kPa x cell area, summed; negative cells count as 0), where it acts
// (its centre of pressure in the mat's frame above: origin at the mat's
// centre, x towards row 0, y towards column 0, m; NaN when the frame reads
// nothing) and the contact area (cells above `contact_kpa`, m^2).
struct FrameLoad {
  double force_n = 0;
  double x_m = NAN, y_m = NAN;
  double contact_m2 = 0;
};
FrameLoad frame_load(const float* frame, const MatSpec& mat, double contact_kpa = kContactKpa);

// Binary R^2 from counts over n cells (the one formula behind eval's
// binary_r2 and training's validation): with both maps binarised, SS_res =
// `mismatches` and SS_tot = n q (1 - q) about the truth's mean q = ones / n,
// so R^2 = 1 - mismatches / (n q (1 - q)). Constant truth (q = 0 or 1):
// 1 if nothing mismatches, 0 otherwise; n = 0: 1. Never NaN.
double binary_r2_from_counts(double mismatches, double ones, double n);

// The index of the first NaN or infinite value of kpa[0, n), n if none
// (a vectorised scan: the writer checks every value it stores).
std::size_t first_non_finite(const float* kpa, std::size_t n);

// Every input format rejects NaN and infinite readings alike: throws Error
// "FILE: WHAT: non-finite value (NaN or Inf) in frame T" (T counted from
// `first_frame`; "FILE: non-finite ..." with `what` empty). kpa: [n / cells
// frames, cells].
void check_finite(const float* kpa, std::size_t n, int cells, const std::string& file, const std::string& what,
                  std::size_t first_frame = 0);

// What a pressure mat can read, kPa: not below zero, and far below what
// would crush bone (human plantar pressure peaks at a few hundred kPa; the
// sensor model saturates at most here, SimSettingsRanges).
inline constexpr Range kPressureRangeKpa{0, 1e6};
// check_finite, then every reading in kPressureRangeKpa: Error "FILE: WHAT:
// -0.5 kPa in frame T, outside [0, 1000000] kPa". The readers of pressure
// (datasets, .npy, imports, live frames) and transfer's input check it.
void check_pressure(const float* kpa, std::size_t n, int cells, const std::string& file, const std::string& what,
                    std::size_t first_frame = 0);

// Body-scale alignment of pressure maps from one body to another, for
// retargeted motion: the same motion on a body `scale` times as tall lands
// `scale` times as far from the centre of the mat (the sequence is centred on
// the mat) with feet `scale` times as long, so each frame is zoomed by `scale`
// about the mat centre (bilinear; cells sampled from outside the mat are 0)
// and multiplied by `gain` (body_gain: the weight ratio over the area ratio,
// so that total force scales with weight).
// in, out: [frames, rows, cols] kPa; in and out must not overlap.
void zoom_frames(const float* in, float* out, int frames, int rows, int cols, double scale, double gain);
PressureSequence zoom_about_centre(const PressureSequence& in, double scale, double gain);
inline double body_scale(double source_height, double target_height) { return target_height / source_height; }
inline double body_gain(double source_height, double source_weight, double target_height, double target_weight) {
  const double s = body_scale(source_height, target_height);
  return target_weight / source_weight / (s * s);
}

}  // namespace ptnet
