// Internal: the steps of the physics bench (see ptnet/physics.hpp).
//
// Dimension legend: T frames of the trial, N plate samples.
#pragma once

#include <vector>

#include "ptnet/physics.hpp"

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
