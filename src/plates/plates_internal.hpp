// Internal: the steps of the physics bench (see ptnet/plates.hpp): the
// force plates' file read, the contacts of a force series, the comparison.
// Tests include it as "plates/plates_internal.hpp".
//
// Dimension legend: T frames of the trial, N plate samples.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "ptnet/c3d.hpp"
#include "ptnet/plates.hpp"

namespace ptnet {

// A trials CSV's coverage ("auto|all|some"; throws Error) and its name.
PlateCoverage parse_plate_coverage(const std::string& text);
const char* plate_coverage_name(PlateCoverage coverage);

// Force plates of a numeric table (OpenSim storage .mot / .sto: a header
// ending in "endheader", named columns, one row per sample; or CSV). A plate
// is every group of columns PREFIX + vx vy vz px py pz whose prefix holds
// "force" ("ground_force_", "1_ground_force_", "ground_force_r_",
// "l_ground_force_" of ptnet's own force files); other columns are neither
// parsed nor kept. Lab axes and units as the file (N, m).
struct ForcePlates {
  struct Plate {
    std::string prefix;
    std::vector<Eigen::Vector3d> force_n;  // [N]
    std::vector<Eigen::Vector3d> cop_m;    // [N]
    std::vector<Eigen::Vector3d> free_moment_nm;  // [N] C3D only (empty from .mot); NaN where cop_m is
  };
  std::vector<double> time_s;  // [N], increasing
  std::vector<Plate> plates;   // [P]
  std::string source;
};
// From the text of a storage file (`source` names it in errors), or read
// from `path` (storage or CSV by its extension, as TableReader has it).
ForcePlates parse_grf_mot(std::string_view text, const std::string& source);
ForcePlates read_grf_mot(const std::string& path);

// ------------------------------------------------------------ C3D plates

// The samples of C3D plates: every analog sample, or one per marker frame
// (the mean of the samples within half a frame of its time).
enum class PlateRate { analog, markers };

// The force plates of a C3D file (types 1-4; docs/formats.md, "C3D
// files"): per plate the ground reaction force on the subject (N), its
// centre of pressure on the plate's surface (m) and its free moment (N m,
// along the plate's normal), in the file's lab frame, on the file's clock
// (ptnet/c3d.hpp). The CoP and free moment are NaN where the vertical force
// is below `cop_min_n`. Errors: no plates, a type other than 1-4, a plate
// whose parameters cannot be used (C3d::plates_problem).
ForcePlates plates_from_c3d(const C3d& c3d, double cop_min_n, PlateRate rate);
// The force plates of `path`, the reader chosen by its extension: .c3d
// (plates_from_c3d at the marker rate: at the analog rate the bench's
// contact threshold would take a plate's millisecond spikes for contacts)
// or OpenSim storage (read_grf_mot; cop_min_n unused).
ForcePlates read_force_plates(const std::string& path, double cop_min_n);

// The contacts of a force series (time_s and force_n of equal length).
std::vector<Contact> find_contacts(const std::vector<double>& time_s, const std::vector<double>& force_n,
                                   double threshold_n, int foot);

}  // namespace ptnet

namespace ptnet::detail {

// v (at times t) at the times `at`: the mean of the samples within
// +/- dt / 2 of each (a box filter: plates faster than the frames), or
// linear between the two either side (slower); NaN outside the samples.
std::vector<double> resample_box(const std::vector<double>& t, const std::vector<double>& v,
                                 const std::vector<double>& at, double dt);

// What a source's figures are compared with the plates by; compare_options
// (bench.cpp) fills it from PhysicsBenchOptions, the one home of each
// threshold (NaN here: not set).
struct CompareOptions {
  double flight_bw = NAN;   // flight: the total force below this (PhysicsBenchOptions::flight_bw)
  double contact_bw = NAN;  // single stance: one foot above this, the other not (contact_n / weight)
  // A stance carries this at its peak; a lighter contact (a swing foot
  // grazing the floor, a seated foot resting) is not one.
  double stance_bw = 0.3;
  double weight_n = NAN;  // the body's weight, N
};
// The frames the figures are over: their times ([T]) and which are
// compared ([T], GaitTrialResult::compared).
struct Frames {
  const std::vector<double>& time_s;
  const std::vector<bool>& compared;
};
// Fills s's figures against `plates` (PhysicsBenchOptions, ForceSource),
// one function a figure: the total force's RMSE and flight recall over the
// compared frames; the peak, stance and loading-rate errors over the
// plates' stances that s matches (whole, every frame compared); the stride
// impulse error over strides all of whose frames are compared; the CoP
// along the foot in single stance.
void compare_with_plates(ForceSource& s, const ForceSource& plates, const Frames& frames,
                         const CompareOptions& options);

}  // namespace ptnet::detail
