// har/bench_internal.hpp (private to the har stage; tests include it as
// "har/bench_internal.hpp"): the benchmark's body bands, the cut of its
// clips, its paired comparisons, and what its setup hands to its run
// (ptnet/har_bench.hpp).
//
// Dimension legend: T frames, N windows, B window frames, H' x W' the
// classifier's input cells.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "har/har_internal.hpp"
#include "ptnet/har.hpp"
#include "ptnet/har_bench.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace ptnet::har {

// A population of bodies: stature and body-mass-index ranges, both sexes.
struct BodyBand {
  std::string name;
  double height_min_cm = 0, height_max_cm = 0;
  double bmi_min = 0, bmi_max = 0;
};

// The named bands (docs/har_bench.md, "Bands"): mid (the recorded
// population, 160-178 cm, BMI 20-25); the deployment bands small (short and
// light), large (tall and heavy), xsmall and xlarge (further out),
// short-light and tall-heavy (milder), light and heavy (build alone), short
// and tall (size alone); all (the transfer model's training bodies,
// covering every other band).
const std::vector<BodyBand>& body_bands();
const BodyBand& body_band(const std::string& name);  // throws Error listing the names

// `count` bodies of a band, ids <prefix>1.., sexes alternating (female
// first), stature and BMI from a Latin hypercube over the band (each of the
// `count` strata of both used once, seeded), weight = BMI x stature^2,
// rounded to 0.1; role as given.
std::vector<BodySpec> band_bodies(const BodyBand& band, int count, std::uint64_t seed,
                                  const std::string& prefix, const std::string& role);

// A clip of `frames` frames cut in time: windows of its training part lie
// in [0, train_end), of its test part in [test_begin, frames), test_begin =
// train_end + one window (the gap). The test part is the last
// kTestFraction of the frames after the gap, at least one window; the
// training part must hold one window too, else usable() is false (clips
// shorter than 3 windows).
struct ClipSplit {
  int frames = 0, train_end = 0, test_begin = 0;
  bool usable() const { return train_end >= kWindowFrames && frames - test_begin >= kWindowFrames; }
};
inline constexpr double kTestFraction = 0.3;
ClipSplit split_clip(int frames);

// Throws Error naming `path` unless it is a training set that
// write_bench_training_set wrote for the same clips with the same split.
void check_bench_training_set(const std::string& path, const BenchOptions& options);

// A source's runs against a baseline's, run by run (throws Error for
// unequal or no runs): their macro_f1, or two series of per-run macro F1.
BenchComparison compare_runs(const BenchSource& source, const BenchSource& baseline);
BenchComparison compare_runs(const std::string& source, const std::vector<double>& source_f1,
                             const std::string& baseline, const std::vector<double>& baseline_f1);

// One usable clip: its source, activity, motion at kFps (whole clip) and split.
struct BenchClip {
  ClipSource source;
  std::string activity;
  Motion motion;  // [T] frames at kFps
  ClipSplit split;
  int label = 0;  // index into BenchClips::activities
};

struct BenchClips {
  std::vector<BenchClip> clips;
  std::vector<std::string> activities;  // sorted
  std::vector<std::string> left_out;    // "what: why"
};

// The clips of options.mocap (clips.csv with an activity column) or the
// procedural ones (activity = category), each loaded and split; clips too
// short to split are left out, and so is an activity left without a clip
// unless options.activities names it (then an error). Throws Error.
BenchClips load_bench_clips(const BenchOptions& options);

void check_bench_training_set(const std::string& path, const BenchClips& clips);

// A progress line "har-bench: ..." when options.progress is set.
void say(const BenchOptions& options, const std::string& line);

// model and model-mean: the sources made by the transfer model.
bool is_transfer_source(const std::string& name);
// The sources a transfer source is compared with: the analytic syntheses.
bool is_baseline(const std::string& name);

// Windows with their labels and deployment body.
struct Windows {
  PreparedWindows inputs;                     // [N, B, H', W']
  std::vector<int> activity, pseudo;          // [N] (pseudo: filled later)
  std::vector<int> body;                      // [N] deployment body index (-1: recorded)
  std::vector<int> source;                    // [N] synthetic: index of the recorded window it came from
  std::vector<std::vector<double>> features;  // [N][F] real windows only
  std::vector<std::string> subject;           // [N] body id (real windows)
  int count() const { return int(activity.size()); }
};

// One training source: the deployment bodies' training windows it adds to
// the recorded ones (none for "recorded").
struct Synthesis {
  std::string name;
  Windows extra;
};

// Every source's classifiers (options.runs each, options.workers at once),
// trained on the recorded windows plus the source's, scored on the test
// windows with `pseudo` or activity labels (bench_score.cpp). The first
// source is the floor, the last the ceiling of the gap.
BenchTable score_table(const std::vector<Synthesis>& sources, const Windows& recorded, const Windows& test,
                       bool pseudo, const std::vector<std::string>& classes, int deployment_bodies,
                       const BenchOptions& options);

}  // namespace ptnet::har
