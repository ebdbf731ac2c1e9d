// har/bench_internal.hpp (private to the har stage): what the benchmark's
// setup hands to its run (ptnet/har_bench.hpp).
//
// Dimension legend: T frames, N windows, B window frames, H' x W' the
// classifier's input cells.
#pragma once

#include <string>
#include <vector>

#include "ptnet/har.hpp"
#include "ptnet/har_bench.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace ptnet::har {

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
