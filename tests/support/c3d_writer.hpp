// Test support: a small C3D writer (c3d.org, "The C3D File Format User
// Guide"), so that the reader's tests and the fuzzer's seeds need no
// committed binary files: every number format (Intel, DEC, MIPS), integer or
// float storage, points, analog channels and force plates.
//
//   C3dSpec s;                        // 2 markers, 3 frames, Intel, floats
//   s.labels = {"RASI", "LASI"};
//   s.xyz = {...};                    // [F, M], NaN: an invalid point
//   C3dImage img = write_c3d(s);      // img.bytes, where its sections are
//
// Dimension legend: F frames, M points, S analog samples (F x per_frame),
// C analog channels, P plates.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "ptnet/c3d.hpp"

namespace ptnet::test {

struct C3dPlateSpec {
  int type = 2;
  std::array<Eigen::Vector3d, 4> corners;   // file units, lab frame
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // file units, as stored
  std::vector<int> channels;                // 1-based, 6 or 8
  std::vector<double> cal_matrix;           // 36 values in column order (type 4)
};

struct C3dSpec {
  C3dFormat format = C3dFormat::intel;
  bool floats = true;                       // float storage; else 16-bit integers x scale
  double scale = 0.125;                     // POINT:SCALE magnitude (integers: the unit of a count)
  double rate_hz = 100;
  int first_frame = 1;
  std::string units = "mm";
  std::vector<std::string> labels;          // [M]
  std::vector<std::string> angles;          // POINT:ANGLES (labels of computed points)
  std::string label_prefix;                 // SUBJECTS:LABEL_PREFIXES (one subject)
  std::vector<Eigen::Vector3d> xyz;         // [F, M] file units; NaN: invalid (residual -1)
  int frames = 0;                           // F (with no points: the analog frames)
  // Analog: the stored values (integers: rounded to 16 bits), per channel
  // scale and offset, the general scale.
  int per_frame = 0;
  std::vector<std::string> analog_labels, analog_units;  // [C]
  std::vector<double> analog_scale, analog_offset;       // [C]
  double gen_scale = 1;
  bool unsigned_analog = false;             // ANALOG:FORMAT UNSIGNED
  std::vector<double> analog;               // [S, C] stored values
  std::vector<C3dPlateSpec> plates;         // [P]
  std::array<int, 2> zero{0, 0};            // FORCE_PLATFORM:ZERO
  std::string company, software;            // MANUFACTURER
};

struct C3dImage {
  std::string bytes;
  std::size_t param_start = 0;   // byte of the parameter section
  std::size_t data_start = 0;    // byte of the first frame
  std::size_t frame_bytes = 0;
};

C3dImage write_c3d(const C3dSpec& spec);

// 4 bytes of `value` in a number format (DEC: VAX F_floating).
std::string c3d_float_bytes(float value, C3dFormat format);

}  // namespace ptnet::test
