// ptnet/c3d.hpp: C3D files, the binary format optical motion-capture systems
// write (c3d.org, "The C3D File Format User Guide"): the 3D points, the
// analog channels and the force plates' parameters of one trial.
//
//   ptnet::C3d c = ptnet::read_c3d("trial.c3d");
//   c.points.markers;                 // [M] names; c.points.at(f, m): file units, NaN = invalid
//   ptnet::Motion m = ptnet::load_motion("trial.c3d", {});   // as for a .trc file
//   c.analog.value(s, ch);            // channel ch at sample s, scaled (ANALOG:SCALE, OFFSET, GEN_SCALE)
//   c.plates[0].type;                 // FORCE_PLATFORM:TYPE; forces: the plates stage
//
// The points are a Trc (ptnet/markers.hpp), so motion_from_trc and
// everything after it take a C3D file as a .trc file. Times are on the
// recording's clock: frame 1 of the capture is t = 0, so a file whose first
// frame is 833 at 250 Hz starts at 3.328 s; analog sample k of the file is at
// the first frame's time + k / analog rate. What is read and what is not:
// docs/formats.md, "C3D files".
//
// Dimension legend: F frames, M markers, S analog samples (F x samples per
// frame), C analog channels, P force plates.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "ptnet/markers.hpp"

namespace ptnet {

// The number format of a file (the processor byte of its parameter section):
// Intel (little-endian, IEEE floats), DEC (little-endian, VAX F floats),
// MIPS (big-endian, IEEE floats).
enum class C3dFormat { intel, dec, mips };
const char* c3d_format_name(C3dFormat format);  // "Intel", "DEC", "MIPS"

// The analog channels, scaled: (stored - OFFSET) x GEN_SCALE x SCALE.
struct C3dAnalog {
  double rate_hz = 0;                          // POINT:RATE x samples per frame
  int per_frame = 0;                           // samples per 3D frame
  std::vector<std::string> labels, units;      // [C] ANALOG:LABELS, ANALOG:UNITS ("" when absent)
  std::vector<double> values;                  // [S, C]
  int channels() const { return int(labels.size()); }
  int samples() const { return channels() ? int(values.size() / labels.size()) : 0; }
  double value(int sample, int channel) const { return values[std::size_t(sample) * labels.size() + std::size_t(channel)]; }
};

// One force plate's parameters (FORCE_PLATFORM group), lengths in metres.
struct C3dPlate {
  int type = 0;                           // TYPE: 1-4 are turned into forces
  std::array<Eigen::Vector3d, 4> corners; // CORNERS, lab frame: quadrants +x+y, -x+y, -x-y, +x-y of the plate
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // ORIGIN as stored (plate frame)
  std::vector<int> channels;              // CHANNEL: the plate's analog channels, 0-based
  std::vector<double> cal_matrix;         // CAL_MATRIX, 36 values in column order; empty when absent
};

struct C3d {
  Trc points;                    // markers (C3D points that are no computed angle, force, moment or power)
  C3dFormat format = C3dFormat::intel;
  bool float_storage = false;    // POINT:SCALE < 0: floats; else integers x POINT:SCALE
  double point_scale = 0;        // POINT:SCALE
  int first_frame = 1;           // of the capture (header, or TRIAL:ACTUAL_START_FIELD)
  std::string units;             // POINT:UNITS ("mm")
  C3dAnalog analog;
  std::vector<C3dPlate> plates;  // [P]
  // FORCE_PLATFORM:ZERO: the frames (1 = the file's first) whose mean is
  // each plate channel's baseline, subtracted before the forces; none unless
  // 1 <= first <= last <= frames ([0, 0] and [1, 0] are common: no baseline).
  std::array<int, 2> plates_zero{0, 0};
  // Why the FORCE_PLATFORM group cannot be used (its arrays shorter than
  // USED, a channel beyond the analog channels): plates is then empty and
  // reading forces is the error "FILE: <plates_problem>"; "" when usable.
  std::string plates_problem;
  std::string manufacturer;      // MANUFACTURER: company, software, version ("" when absent)
  std::string source;
};

// Reads a C3D file. A file that is not one, truncated, or whose counts
// do not fit its size is an Error of one line ("trial.c3d: expected 324
// frames of 2288 bytes from byte 16384, found 402112 bytes (a truncated
// file?)"); every count is checked against the file's size before anything
// is allocated.
C3d read_c3d(const std::string& path);

}  // namespace ptnet
