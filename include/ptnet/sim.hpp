// ptnet/sim.hpp: the pressure-mat simulator. A motion on the canonical
// skeleton of a body, pressed onto a mat, frame by frame.
//
//   ptnet::Body body(ptnet::BodySpec{"b1", ptnet::Sex::male, 180, 80});
//   ptnet::Motion m = ptnet::retarget(ptnet::load_motion("walk.bvh", {}), 180);
//   ptnet::SimOptions opt;                       // 80 x 28 x 0.02 m, fixed mat
//   ptnet::PressureSequence seq = ptnet::simulate(m, body, opt);   // [T, 80, 28] kPa
//
// Several bodies of one motion: place the source motion once, so that every
// copy lies along the same axis (simulate_dataset does this):
//   ptnet::Motion src = ptnet::load_motion("walk.bvh", {});
//   ptnet::MotionPlacement place = ptnet::place_motion(src, opt);
//   for (double h : {150.0, 190.0})
//     seqs.push_back(ptnet::simulate(ptnet::retarget(src, h), body_of(h), opt,
//                                    place.scaled(ptnet::retarget_scale(src, h))));
//
// Per frame (docs/simulate.md, "Physics"):
//  1. placement (MotionPlacement below): the whole sequence is centred on the
//     mat and its walking direction (principal axis of the pelvis path; the
//     mean facing direction if it barely moves) laid along the mat's long
//     axis, pointing to row 0 (+x end); the body's left is col 0 (see
//     ptnet/pressure.hpp). `follow` re-centres the mat on the smoothed pelvis
//     path each frame. The placement is decided once per source motion and
//     scaled to each retargeted copy, so that one motion lies the same way on
//     every body and the copies differ by a zoom about the mat centre by the
//     height ratio (zoom_about_centre).
//     Rigs whose toe joint is not at the metatarsal heads (the ankle -> toe
//     bone of a planted foot flatter or steeper than the canonical 20.8
//     degrees) have their feet pitched back to the canonical sole.
//     The floor is z = 0, corrected for capture drift: the lower envelope of
//     the planted (slow, level) soles over floor_window_s, bounded to +/- 25 cm.
//     Like the mat's axis and centre, it is decided once per source motion
//     (on its copy at a reference height) and scaled to every copy, so that
//     which frames touch the ground does not depend on the body.
//  2. depth from below: the lowest body surface above each of S x S samples
//     per cell (foot soles, lower surfaces of the segment capsules), on the
//     mat and beside it.
//  3. contact: a frame has ground contact when some surface lies within the
//     compliance band (default 20 mm) of the ground; otherwise it is airborne.
//  4. load: F = m (g + a_z), a_z the low-passed vertical acceleration of the
//     segment-mass centre of mass, clamped at 0; zero with no contact.
//  5. elastic foundation: the body sinks into the sole tissue and mat foam
//     (linear stiffness k) until it carries F, in four steps. Sink level: s
//     solves sum_samples k max(0, s - z) dA = F, at most max_sink_m above the
//     lowest surface point. Penetration: each cell's mean max(0, s - z).
//     Tilt (balance_moments): the penetrations weighted so that the centre
//     of pressure moves towards the zero-moment point of the centre of mass,
//     x_com - z_com a_xy / (g + a_z) (within 0.6 standard deviations of the
//     contact): weight shifts from heel to toe as the body passes over the
//     foot, and between the feet. Load scaling: sum(pressure x cell area) = F
//     over all contact, before the sensor model; contact off the mat takes
//     its share but is not sensed. So a heavier load sinks deeper and widens
//     the contact (toe-off, heel strike) instead of piling onto a few cells.
//     With a trace, who carries what (FrameTrace below).
//  6. sensor: crosstalk blur, saturation, noise, activation threshold,
//     quantisation.
// Same options (seed included): same bytes. Another seed changes only the noise.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/pressure.hpp"
#include "ptnet/progress.hpp"

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
  double compliance_m = 0.020;           // contact: some surface within this height of the ground (mat and
                                         // sole compliance, ~1 cm, plus the capture's foot-height error)
  double stiffness_kpa_per_mm = 6.0;     // elastic foundation: kPa per mm of penetration (sets the sink depth)
  double max_sink_m = 0.025;             // the sink level stays within this of the lowest surface point
  double floor_window_s = 1.0;           // capture floor followed over this window (+/- 25 cm; 0: z = 0 is the floor)
  bool balance_moments = true;           // tilt the foundation: centre of pressure towards the CoM's zero-moment point
  int subsamples = 3;                    // S: S x S depth samples per cell
  double com_filter_hz = 4.0;            // low-pass cutoff of the CoM acceleration (Hz; Winter: 4-6 Hz for gait kinematics)
  SensorModel sensor;                    // see above
  std::uint64_t seed = 0;                // noise stream
};

// A noiseless sensor (the physics only): for tests and references.
SensorModel ideal_sensor();

// The simulator's settings as its front ends take them (`ptnet simulate`'s
// flags, Python's simulate() arguments): one mapping to SimOptions
// (sim_options) with one set of defaults and ranges.
struct SimSettings {
  int rows = kMatRows, cols = kMatCols;  // mat cells (H x W)
  double pitch_m = kMatPitchM;           // cell size (m)
  std::string placement = "fixed";       // fixed | follow (parse_placement)
  double compliance_mm;                  // contact band above the ground (mm): SimOptions::compliance_m
  int subsamples;                        // depth samples per cell side: SimOptions::subsamples
  bool ideal_sensor = false;             // ideal_sensor() instead of the default SensorModel
  // Overrides of the sensor model's values (unset: the model's, default or ideal).
  std::optional<double> crosstalk, saturation_kpa, noise_kpa, threshold_kpa, quantum_kpa;
  std::uint64_t seed = 0;                // SimOptions::seed
  SimSettings();
};
// The values each SimSettings field accepts: sim_options() checks them,
// `ptnet simulate`'s validators show them.
struct SimSettingsRanges {
  Range rows{1, 1000}, cols{1, 1000}, pitch_m{0.001, 0.2}, compliance_mm{1, 50}, subsamples{1, 16};
  Range crosstalk{0, 0.24}, saturation_kpa{0, 1e6, true}, noise_kpa{0, 1e4}, threshold_kpa{0, 1e6},
      quantum_kpa{0, 1e6};
};
inline constexpr SimSettingsRanges kSimSettingsRanges{};

// The SimOptions of `settings`; throws Error naming the first field out of
// its range ("crosstalk: 0.3 is not in [0, 0.24]") or an unknown placement.
SimOptions sim_options(const SimSettings& settings);

// Where the mat lies under a motion: world -> mat coordinates in frame t,
// X = axis . (p - centre[t]) (towards row 0), Y = left . (p - centre[t])
// (towards col 0); centre is constant for Placement::fixed.
struct MotionPlacement {
  Eigen::Vector2d axis{1, 0}, left{0, 1};
  Eigen::Vector2d anchor{0, 0};          // frame 0's pelvis (x, y): retarget scales the root path about it
  std::vector<Eigen::Vector2d> centre;   // [T] world (x, y), m
  std::vector<double> floor;             // [T] height of the capture floor under the motion, m (empty: z = 0)
  // Each foot's pitch correction [left, right] (rad, toe down > 0; 0: none),
  // decided on the motion's kFloorReferenceHeightCm copy: an angle, the same
  // on every copy (decided per copy otherwise, the "planted" speed test would
  // pass other frames on a short copy).
  std::array<double, 2> foot_pitch{0, 0};
  // Each foot's height correction [left, right] (m, lowered > 0): the level
  // its sole stands at, the 20th percentile over the motion of its lowest
  // surface point above the floor, when 5 mm to 3 cm above it (a capture or
  // retargeting error: a foot floating above the floor it stands on, as
  // marker-derived joint centres leave it); 0 otherwise (a foot held up, or
  // one at or below the floor, which already presses into the foundation).
  // Found on the same reference copy as the pitch, scaled to each copy.
  std::array<double, 2> foot_lift{0, 0};
  // The placement of a copy whose horizontal root path is this motion's
  // scaled by `ratio` about `anchor` (a retargeted copy: ratio =
  // retarget_scale(source, height_cm)): same axis, centres and floor scaled.
  MotionPlacement scaled(double ratio) const;
};

// What a motion lacks to carry its own dynamics (docs/physics.md, "Motions
// that cannot carry their dynamics").
struct MotionDynamics {
  // Frames in stretches of at least 0.5 s whose pelvis height is fixed (to
  // 1 micrometre a frame) while a foot steps (moves faster than 0.3 m/s):
  // a rig that drives the hips by rotations only. No load model finds a
  // flight or a bounce in them: their load stays near body weight.
  double frozen_pelvis = 0;
  // Frames where no body surface is on the floor (within the compliance
  // band) and that are no flight: a stretch off the floor longer than 0.6 s,
  // or one over 0.15 s through which the centre of mass does not fall (its
  // mean vertical acceleration inside is above -g / 2): the body stands on
  // something that is not the floor (steps, objects), and those frames read
  // no load.
  double unsupported = 0;
  // Frames where the load's point (the zero-moment point) stays more than
  // 5 cm outside the feet on the floor for 0.3 s or longer: something else
  // carries part of the body (a seat: a body that sits does not fall). The
  // feet then carry what balances the load's moment about a seat under the
  // hips (FrameTrace::carried_n the rest), which a mat under the feet does
  // not sense.
  double carried = 0;
};
// The check, on the motion's copy at kFloorReferenceHeightCm as placed by
// `placed` (place_motion(motion, options); nullptr: placed here).
MotionDynamics check_dynamics(const Motion& motion, const SimOptions& options,
                              const MotionPlacement* placed = nullptr);
// "002_03: ..." one line per finding (none when the motion carries its dynamics).
std::vector<std::string> dynamics_warnings(const std::string& name, const MotionDynamics& dynamics);

// The placement of `motion` for options.placement (fixed: the pelvis path's
// bounding box centred; follow: its Gaussian-smoothed path, sigma
// options.follow_smoothing_s), its feet's pitch correction and its floor
// (options.floor_window_s), both found on the motion retargeted to
// kFloorReferenceHeightCm (the floor scaled back). Throws Error for an empty
// motion.
MotionPlacement place_motion(const Motion& motion, const SimOptions& options);
inline constexpr double kFloorReferenceHeightCm = 170.0;
// The placement of source's copy retargeted onto a body of height_cm:
// place_motion(source, options).scaled(retarget_scale(source, height_cm)).
MotionPlacement place_copy(const Motion& source, double height_cm, const SimOptions& options);

// Simulates `motion` (already retargeted onto `body`: canonical joints, world,
// m, ground z = 0) on the mat: [T = motion.size(), rows, cols] kPa at
// motion.fps, placed by place_motion(motion, options). Throws Error for an
// empty motion or impossible options.
PressureSequence simulate(const Motion& motion, const Body& body, const SimOptions& options);

// What simulate() attributes to each foot in one frame (before the sensor model).
struct FootLoad {
  double force_n = 0;     // vertical load carried by this foot's sole (N), on or off the mat
  double heel_n = 0;      // of which under the heel (sole u < 0.3)
  double forefoot_n = 0;  // of which under the metatarsal heads and toes (u >= 0.6)
  double cop_u = -1;      // centre of pressure along the sole, 0 heel back .. 1 toe tip; -1: unloaded
  double area_m2 = 0;     // contact area of the sole (penetration > 0)
};
struct FrameTrace {
  std::array<FootLoad, 2> foot;  // [left, right]
  double load_n = 0;             // F of the frame (N); 0 when airborne
  double other_n = 0;            // carried by other body parts (knees, hands, ...)
  double carried_n = 0;          // carried off the floor, by a seat (MotionDynamics::carried); not in load_n
  double sink_m = 0;             // sink level above the lowest surface point (m)
};

// simulate() that also fills trace[T] (per-foot load, heel / forefoot split,
// centre of pressure along each sole): for tests, gait analysis and figures.
PressureSequence simulate(const Motion& motion, const Body& body, const SimOptions& options,
                          std::vector<FrameTrace>* trace);

// The simulated vertical ground reaction per frame, from a trace: total and
// per foot, in N, and the centre of pressure along each loaded foot (0 heel
// .. 1 toe); `ptnet simulate --forces` writes one per sequence.
//   std::vector<ptnet::FrameTrace> trace;
//   ptnet::simulate(motion, body, opt, &trace);
//   ptnet::write_force_table(ptnet::force_table(trace, motion, body), "walk.mot", false);
struct ForceTable {
  double mass_kg = 0;
  std::vector<double> time_s;                 // [T] the motion's clock (Motion::start_s + t / fps)
  std::vector<double> total_n;                // [T] on and off the mat, every body part
  std::vector<std::array<double, 2>> foot_n;  // [T] [left, right]
  std::vector<std::array<double, 2>> cop_u;   // [T] [left, right]; NaN: foot unloaded
  std::vector<double> carried_n;              // [T] carried off the floor by a seat (FrameTrace::carried_n)
  // [T] [left, right] where each foot's load acts, on the floor (m): the
  // point cop_u along the foot's heel-toe line (foot_ends) of the motion's
  // frame, x and y of its world (z up); (0, 0) when the foot is unloaded.
  // Empty: not known (written as unloaded).
  std::vector<std::array<Eigen::Vector2d, 2>> cop_m;
};
ForceTable force_table(const std::vector<FrameTrace>& trace, const Motion& motion, const Body& body);
// Writes the table as an OpenSim storage file (.mot or .sto: time, then
// total_force_vy, total_force_bw, l_/r_ground_force_vy, l_/r_force_bw,
// l_/r_cop_u, carried_bw, then each foot's whole plate group
// l_/r_ground_force_vx, vz, px, py, pz) or as CSV (.csv, the same columns),
// atomically; refuses to overwrite unless `force`. The groups are in
// OpenSim's axes, y up: the force (0, vy, 0) N acting at (px, 0, pz) =
// (y, 0, x) of cop_m (m; 0 when unloaded), the inverse of the lab-to-world
// swap of a y-up file, so that the file reads back as two force plates, one
// a foot (ptnet physics-bench, OpenSim).
void write_force_table(const ForceTable& table, const std::string& path, bool force);

// simulate() with a given placement (place_copy: the source motion's,
// scaled), used whatever options.placement says; trace as above. Throws Error
// if placement.centre does not have one entry per frame.
PressureSequence simulate(const Motion& motion, const Body& body, const SimOptions& options,
                          const MotionPlacement& placement, std::vector<FrameTrace>* trace = nullptr);

// One simulation job for simulate_many.
struct SimJob {
  const Motion* motion = nullptr;  // on this body
  const Body* body = nullptr;
  std::uint64_t seed = 0;          // replaces options.seed for this job
  const MotionPlacement* placement = nullptr;  // null: place_motion(*motion, options)
  // The same pressure read again by the sensor with each of these seeds (the
  // noise-floor copies of simulate_dataset), for the cost of the sensor
  // model alone; into simulate_many's *rereads.
  std::vector<std::uint64_t> reread_seeds;
};

// Runs every job on `threads` threads (0: hardware concurrency); result i is
// job i, identical whatever the thread count; with `rereads`, (*rereads)[i][k]
// is job i read with seed reread_seeds[k]; with `forces`, (*forces)[i] is job
// i's force_table (its trace: a slower simulation). `progress` gets a count
// {"simulate", done, total, "sequences"} from the worker threads
// (serialised), if given.
std::vector<PressureSequence> simulate_many(const std::vector<SimJob>& jobs, const SimOptions& options,
                                            int threads, const ProgressFn& progress = {},
                                            std::vector<std::vector<PressureSequence>>* rereads = nullptr,
                                            std::vector<ForceTable>* forces = nullptr);

// A per-sequence seed from a run seed and the sequence name (FNV-1a + mix).
std::uint64_t sequence_seed(std::uint64_t seed, const std::string& name);
// The sensor seed of a sequence's noise-floor copy: sequence_seed(seed,
// name + "/floor") (no sequence name holds '/', so it is no other's seed).
std::uint64_t floor_seed(std::uint64_t seed, const std::string& name);

}  // namespace ptnet
