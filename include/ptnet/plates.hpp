// ptnet/plates.hpp: the simulator checked against real force plates (the
// simulator's own ground reaction forces: ForceTable, ptnet/sim.hpp).
//
//   auto trials = ptnet::read_gait_trials("bench/real-gait.csv", "real-gait");
//   ptnet::GaitTrialResult r = ptnet::run_gait_trial(trials[0], {});  // plates vs simulator vs naive
//   ptnet::write_physics_report({r}, "physics", /*force=*/false);     // results.json + index.html
//
// Units: N, s, m; BW = body weight (m g). Vertical is the lab's vertical
// axis of the marker file (detected, see ptnet/markers.hpp).
//
// Dimension legend: T simulated frames.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"

namespace ptnet {

// ------------------------------------------------------------------ gait

// One foot's contact: a run of samples above the contact threshold, its
// ends interpolated to where the force crosses it.
struct Contact {
  int foot = 0;                  // 0 left, 1 right
  double start_s = 0, end_s = 0;
  double peak_n = 0;             // largest force in the contact
  double impulse_ns = 0;         // integral of the force over the contact (trapezoids)
  double loading_rate_n_s = 0;   // 20 % -> 80 % of the peak on the rising edge, over its duration
  bool whole = true;             // begins and ends inside the series (false: cut by its first or last sample)
};

// Which steps the plates see: `all` (a treadmill, an instrumented walkway:
// every frame is compared), `some` (plates set in an overground walkway: a
// contact of the simulator's that the plates do not see is left out of the
// figures) or `automatic` ("auto" in a trials CSV: `some` when the plates
// miss one of the simulator's contacts, else `all`).
enum class PlateCoverage { automatic, all, some };

// A trial of a gait lab: markers, plates and the subject.
struct GaitTrial {
  std::string name;
  std::string markers, static_markers, plates;  // paths; static may be ""
  std::string marker_map;                      // "": chosen
  BodySpec body;                               // the subject (sex, stature, mass)
  PlateCoverage coverage = PlateCoverage::automatic;
  Units units = Units::automatic;  // the markers' unit; automatic: the file's Units header
};
// The columns of a trials CSV, the one list that read_gait_trials reads,
// `ptnet physics-bench --help` prints and docs/physics.md documents (a test
// holds the page to it).
struct GaitTrialColumn {
  const char* name;
  bool required;
};
inline constexpr GaitTrialColumn kGaitTrialColumns[] = {
    {"trial", true},     {"markers", true},     {"plates", true},    {"sex", true},        {"height_cm", true},
    {"weight_kg", true}, {"static", false},     {"marker_map", false}, {"coverage", false},
    {"units", false}};
// "trial,markers,plates,sex,height_cm,weight_kg[,static,marker_map,coverage,units]"
std::string gait_trial_columns_text();

// A trials CSV (docs/physics.md; kGaitTrialColumns). Paths (markers, plates,
// static, and marker_map unless it names a shipped map) are relative to
// `data_dir` ("": the CSV's folder), as the filesystem resolves them
// (resolved_path). Checked before any trial runs: each file there and a
// regular file (InputFile's words for what else it is), each trial name a
// file name of the report (name_problem, ptnet/strings.hpp) and no two the
// same.
std::vector<GaitTrial> read_gait_trials(const std::string& csv, const std::string& data_dir);

struct PhysicsBenchOptions {
  double fps = 0;             // simulation rate; 0: the marker file's
  SimOptions sim;             // how to simulate (ideal sensor; the mat follows the body)
  double contact_n = 20;      // a foot is in contact above this force (N)
  double flight_bw = 0.05;    // a frame is in flight below this total force (BW)
  double assign_m = 0.15;     // a plate's force belongs to the foot within this distance of its CoP
                              // (horizontal distance to the heel-toe line plus the foot's height)
  PhysicsBenchOptions();
};

// One source of a vertical force (the plates, the simulator, the naive
// reference) on the trial's frames, and its figures against the plates.
struct ForceSource {
  std::string name;
  std::vector<double> total_bw;                // [T]
  std::vector<std::array<double, 2>> foot_bw;  // [T] [left, right]
  std::vector<std::array<double, 2>> cop_u;    // [T] NaN: unloaded or unknown
  std::vector<Contact> contacts;
  // Against the plates (NaN for the plates themselves); per-contact figures
  // over the plates' whole contacts (Contact::whole):
  double rmse_bw = NAN;           // total force, over the compared frames
  double peak_error_pct = NAN;    // mean |peak - plates' peak| / plates' peak over matched contacts
  double stance_error_ms = NAN;   // mean |stance - plates' stance|
  double loading_rate_error_pct = NAN;
  double stride_impulse_error_pct = NAN;  // mean |impulse - plates'| over the plates' strides
  double flight_recall = NAN;     // fraction of the plates' flight frames below flight_bw here
  double cop_rms = NAN;           // CoP along the foot in single stance, RMS difference (foot lengths)
  int matched = 0;                // contacts matched to the plates'
};

struct GaitTrialResult {
  GaitTrial trial;
  double fps = 0;
  std::vector<double> time_s;  // [T]
  ForceSource plates, simulated, naive;
  PlateCoverage coverage = PlateCoverage::all;  // all or some (GaitTrial::coverage decided)
  std::vector<bool> compared;  // [T] the frames the figures are over
  int carried_frames = 0;      // left out: a seat carries part of the body (MotionDynamics::carried)
  int flight_frames = 0;       // the plates' frames below flight_bw (compared)
  int single_stance_frames = 0;
  double belt_mps = 0;         // the treadmill belt removed
  ForceTable table;            // the simulator's forces (write_force_table)
};
GaitTrialResult run_gait_trial(const GaitTrial& trial, const PhysicsBenchOptions& options);

// What a result's figures rest on, checked before they are reported
// (physics-bench runs it on every trial before it writes anything). Throws
// Error (FILE: the trial's plates) naming the trial when nothing can be
// compared: no plate sample within the markers' times (plates on another
// clock), a vertical force below zero in most frames (the force on the
// plates, a common export convention, not the ground reaction: refused, with
// the hint to negate it, rather than flipped, since a sign that is wrong for
// another reason, a wrong vertical axis or a plate's calibration, would then
// give figures silently), no load on the plates, or no frame compared.
// Returns warnings: the plates covering only part of the trial's frames (the
// fraction and the times).
std::vector<std::string> check_gait_result(const GaitTrialResult& result, const PhysicsBenchOptions& options);

// `out_dir`/results.json, index.html (force against time, per trial), and
// per trial <trial>_sim.mot (the simulator's forces), <trial>_frames.csv
// (every frame of plates, simulator and naive reference), <trial>_total.svg,
// <trial>_feet.svg and <trial>_cop.svg (the CoP along each loaded foot);
// refuses to overwrite unless `force`.
// (check_physics_report first; the files appear together at the end, or none).
void write_physics_report(const std::vector<GaitTrialResult>& results, const std::string& out_dir, bool force);
// What write_physics_report checks before it writes, for before the work:
// each trial's name a file name (name_problem), no file written twice, the
// folder no file and existing outputs only with `force`.
void check_physics_report(const std::vector<GaitTrial>& trials, const std::string& out_dir, bool force);

}  // namespace ptnet
