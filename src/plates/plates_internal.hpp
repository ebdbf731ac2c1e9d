// Internal: the steps of the physics bench (see ptnet/plates.hpp): the
// force plates' file read, the contacts of a force series, the comparison.
// Tests include it as "plates/plates_internal.hpp".
//
// Dimension legend: T frames of the trial, N plate samples.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "ptnet/plates.hpp"

namespace ptnet {

// A plate's sample of a force or a position, kept in single precision (7
// significant digits: 1 mN in 10 kN, 1 micrometre in 10 m, beyond what
// plates measure); reads as an Eigen::Vector3d.
struct PlateVector {
  std::array<float, 3> v{};
  PlateVector() = default;
  PlateVector(double x, double y, double z) : v{float(x), float(y), float(z)} {}
  PlateVector(const Eigen::Vector3d& p) : PlateVector(p.x(), p.y(), p.z()) {}  // NOLINT: implicit, as Eigen's
  double operator[](int i) const { return v[std::size_t(i)]; }
  operator Eigen::Vector3d() const { return {v[0], v[1], v[2]}; }  // NOLINT
};

// Force plates of a numeric table (OpenSim storage .mot / .sto: a header
// ending in "endheader", named columns, one row per sample; or CSV). A plate
// is every group of columns PREFIX + vx vy vz px py pz whose prefix holds
// "force" ("ground_force_", "1_ground_force_", "ground_force_r_",
// "l_ground_force_" of ptnet's own force files); other columns are neither
// parsed nor kept. Lab axes and units as the file (N, m).
struct ForcePlates {
  struct Plate {
    std::string prefix;
    std::vector<PlateVector> force_n;  // [N]
    std::vector<PlateVector> cop_m;    // [N]
  };
  std::vector<double> time_s;  // [N], increasing
  std::vector<Plate> plates;   // [P]
  std::string source;
};
// From the text of a storage file (`source` names it in errors), or read
// from `path` (storage or CSV by its extension, as TableReader has it).
ForcePlates parse_grf_mot(std::string_view text, const std::string& source);
ForcePlates read_grf_mot(const std::string& path);

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

struct CompareOptions {
  double flight_bw = 0.05;   // flight: the total force below this
  double contact_bw = 0.03;  // single stance: one foot above this, the other not
};
// Fills s's figures against `plates` (PhysicsBenchOptions, ForceSource)
// over the frames `compared` marks ([T]): a stride counts when all its
// frames are compared, a contact when the plates saw it whole.
void compare_with_plates(ForceSource& s, const ForceSource& plates, const std::vector<double>& time_s,
                         const std::vector<bool>& compared, const CompareOptions& options);

}  // namespace ptnet::detail
