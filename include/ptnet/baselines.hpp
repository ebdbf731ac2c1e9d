// ptnet/baselines.hpp: the two naive transfer baselines of the evaluation and
// the RMSE they are compared with (shared by the model, train and eval stages).
//
//   auto copy = ptnet::baseline_copy(src);                           // unchanged
//   auto scaled = ptnet::baseline_weight_scale(src, source, target); // x w_t / w_s
//   double e = ptnet::rmse_kpa(scaled, truth);                       // kPa
#pragma once

#include "ptnet/body_spec.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

// The source sequence unchanged: [T, rows, cols], kPa.
PressureSequence baseline_copy(const PressureSequence& src);

// Every cell scaled by target.weight_kg / source.weight_kg (the same contact
// area carrying the target's weight): [T, rows, cols], kPa.
PressureSequence baseline_weight_scale(const PressureSequence& src, const BodySpec& source,
                                       const BodySpec& target);

// Root mean square difference over all cells and frames, kPa. Throws Error
// if the mats or frame counts differ.
double rmse_kpa(const PressureSequence& a, const PressureSequence& b);

}  // namespace ptnet
