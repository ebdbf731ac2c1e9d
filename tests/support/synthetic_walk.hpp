// support/synthetic_walk.hpp (test support: tests and benchmarks, not the
// library): a synthetic walk, not the simulator.
//
//   ptnet::PressureSequence s = ptnet::synthetic_walk(ptnet::MatSpec{}, 90, 30, 170, 70, /*seed=*/1);
//
// A walker crossing the mat from the near end (last row) towards row 0,
// left foot on the left columns, heel-to-toe roll-over blobs whose size
// scales with height and whose load scales with weight, sensor noise and a
// 1 kPa activation threshold.
//
// Dimension legend: T frames, H x W mat cells; the result is [T, H, W] kPa.
#pragma once

#include "ptnet/pressure.hpp"

namespace ptnet {

PressureSequence synthetic_walk(const MatSpec& mat, int frames, double fps, double height_cm,
                                double weight_kg, unsigned long long seed);

}  // namespace ptnet
