// har/standin.hpp (private to the har stage; tests include it through the
// stage's private include path): the stand-in sensor's internals.
//
//   std::vector<float> gain = ptnet::har::standin_gain_map(mat, options);  // [H, W], 0 = dead
//
// Dimension legend: H x W mat cells.
#pragma once

#include <vector>

#include "ptnet/har.hpp"

namespace ptnet::har {

// The per-cell gain map and dead cells of the stand-in sensor: [H, W] gains
// (0 = dead), deterministic in the seed.
std::vector<float> standin_gain_map(const MatSpec& mat, const StandinOptions& options);

}  // namespace ptnet::har
