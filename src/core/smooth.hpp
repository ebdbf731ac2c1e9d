// core/smooth.hpp: the Gaussian smoothing of a series, shared by the motion
// stage (retargeting's foot correction) and the simulator (the centre of
// mass's acceleration, the capture floor, the followed path).
//
//   std::vector<double> y = ptnet::gaussian_smooth(x, 2.5);  // sigma in samples
//
// Private to the library (not installed): the stages include it as
// "core/smooth.hpp".
#pragma once

#include <vector>

namespace ptnet {

// x [N] convolved with a Gaussian of `sigma` samples (truncated at 3 sigma,
// renormalised at the ends, so a constant stays constant); x itself when
// sigma < 0.3 or N < 2.
std::vector<double> gaussian_smooth(const std::vector<double>& x, double sigma);

}  // namespace ptnet
