// ptnet/sim.hpp: the pressure-mat simulator. A motion on the canonical
// skeleton of a body, pressed onto a mat, frame by frame.
//
//   ptnet::Body body(ptnet::BodySpec{"b1", ptnet::Sex::male, 180, 80});
//   ptnet::Motion m = ptnet::retarget(ptnet::load_motion("walk.bvh", {}), 180);
//   ptnet::SimOptions opt;                       // 80 x 28 x 0.02 m, fixed mat
//   ptnet::PressureSequence seq = ptnet::simulate(m, body, opt);   // [T, 80, 28] kPa
//
// Per frame (../shared/design.md, "Pressure simulation"):
//  1. placement: the whole sequence is centred on the mat and its walking
//     direction (principal axis of the pelvis path; the mean facing direction
//     if it barely moves) laid along the mat's long axis, pointing to row 0
//     (+x end); the body's left is col 0 (see ptnet/pressure.hpp). `follow`
//     re-centres the mat on the smoothed pelvis path each frame.
//  2. depth from below: the lowest body surface above each of S x S samples
//     per cell (foot soles, lower surfaces of the segment capsules).
//  3. contact: samples within the compliance band; penetration = band - depth.
//  4. load: F = m (g + a_z), a_z the low-passed vertical acceleration of the
//     segment-mass centre of mass, clamped at 0; zero with no contact. F is
//     shared over the contact cells in proportion to their mean penetration
//     (elastic foundation), so sum(pressure x cell area) = F for a body wholly
//     on the mat, before the sensor model. Contact off the mat takes its share
//     but is not sensed.
//  5. sensor: crosstalk blur, saturation, noise, activation threshold,
//     quantisation.
// Same options (seed included): same bytes. Another seed changes only the noise.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

enum class Placement { fixed, follow };
Placement parse_placement(const std::string& text);  // "fixed|follow"; throws Error
const char* placement_name(Placement placement);

struct SensorModel {
  double crosstalk = 0.02;        // fraction of a cell's reading leaking to each of its 4 neighbours
  double saturation_kpa = 600.0;  // readings clip here (typical resistive mat range)
  double noise_sd_kpa = 0.2;      // Gaussian read noise on every cell, seeded
  double threshold_kpa = 1.0;     // readings below this are 0 (activation threshold)
  double quantum_kpa = 0.1;       // ADC step; readings are rounded to a multiple (0: off)
};

struct SimOptions {
  MatSpec mat;                           // 80 x 28 cells of 0.02 m
  Placement placement = Placement::fixed;  // fixed: a physical mat; follow: re-centred each frame
  double follow_smoothing_s = 1.0;       // follow: Gaussian sigma of the pelvis path smoothing (s)
  double compliance_m = 0.010;           // surfaces within this height of the ground are in contact
  int subsamples = 3;                    // S: S x S depth samples per cell
  double com_filter_hz = 6.0;            // low-pass cutoff of the CoM vertical acceleration
  SensorModel sensor;                    // see above
  std::uint64_t seed = 0;                // noise stream
};

// A noiseless sensor (the physics only): for tests and references.
SensorModel ideal_sensor();

// Simulates `motion` (already retargeted onto `body`: canonical joints, world,
// m, ground z = 0) on the mat: [T = motion.size(), rows, cols] kPa at
// motion.fps. Throws Error for an empty motion or impossible options.
PressureSequence simulate(const Motion& motion, const Body& body, const SimOptions& options);

// Total vertical load (N) per frame, F = m (g + a_z) clamped at 0 (before the
// contact test): [T], N.
std::vector<double> vertical_load(const Motion& motion, const Body& body, double com_filter_hz);

// One simulation job for simulate_many.
struct SimJob {
  const Motion* motion = nullptr;  // on this body
  const Body* body = nullptr;
  std::uint64_t seed = 0;          // replaces options.seed for this job
};

// Runs every job on `threads` threads (0: hardware concurrency); result i is
// job i, identical whatever the thread count. `progress(done, total)` is
// called from the worker threads (serialised), if given.
std::vector<PressureSequence> simulate_many(const std::vector<SimJob>& jobs,
                                            const SimOptions& options, int threads,
                                            const std::function<void(int done, int total)>& progress = {});

// A per-sequence seed from a run seed and the sequence name (FNV-1a + mix).
std::uint64_t sequence_seed(std::uint64_t seed, const std::string& name);

}  // namespace ptnet
