// har/standin.hpp (private to the har stage; tests include it through the
// stage's private include path): the stand-in sensor's internals.
//
//   std::vector<float> gain = ptnet::har::standin_gain_map(mat, options);  // [H, W], 0 = dead
//   ptnet::har::degrade(sequence, gain, sim.sensor);    // the stand-in's mat reading a simulation
//
// Dimension legend: H x W mat cells.
#pragma once

#include <vector>

#include "ptnet/har.hpp"
#include "ptnet/sim.hpp"

namespace ptnet::har {

// The per-cell gain map and dead cells of the stand-in sensor: [H, W] gains
// (0 = dead), deterministic in the seed.
std::vector<float> standin_gain_map(const MatSpec& mat, const StandinOptions& options);

// The simulator options of the stand-in: its crosstalk, noise, placement
// and seed on the default mat.
SimOptions standin_sim_options(const StandinOptions& options);

// The degraded sensor on a simulated sequence [T, H, W], in place: each
// cell times its gain (dead cells 0), then the activation threshold,
// saturation and ADC step of `sensor` again.
void degrade(PressureSequence& sequence, const std::vector<float>& gain, const SensorModel& sensor);

// A sequence that did not come from the mat (a transfer's output) read by
// it, in place: the sensor's Gaussian noise (seeded), dead cells (gain 0)
// at 0, threshold, saturation and ADC step. The per-cell gains are not
// applied: a user does not know them.
void read_again(PressureSequence& sequence, const std::vector<float>& gain, const SensorModel& sensor,
                std::uint64_t seed);

}  // namespace ptnet::har
