// har/bench_internal.hpp (private to the har stage): what the benchmark's
// setup hands to its run (ptnet/har_bench.hpp).
//
// Dimension legend: T frames.
#pragma once

#include <string>
#include <vector>

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

}  // namespace ptnet::har
