// core/rate.hpp: "the same frame rate", decided once for every stage: a
// motion file read at a rate as it is (no resampling), a sequence written
// into a dataset, shards merged, a sequence given to a model, a model
// resumed on a dataset.
//
//   ptnet::same_rate(59.9988, 60)   // true: a BVH's Frame Time 0.016667
//   ptnet::same_rate(59.9, 60)      // false: resample
//
// Private to the library (not installed): the stages include it as
// "core/rate.hpp".
#pragma once

#include <cmath>

namespace ptnet {

// Relative difference within which two frame rates are one: a header's rate
// rounded to a few digits (Frame Time 0.016667 s is 60 fps to 2e-5).
inline constexpr double kSameRateTolerance = 1e-4;

// True when `fps` is the rate `reference` up to kSameRateTolerance.
inline bool same_rate(double fps, double reference) {
  return std::abs(fps - reference) <= kSameRateTolerance * std::abs(reference);
}

}  // namespace ptnet
