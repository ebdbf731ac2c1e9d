// ptnet/simulate_dataset.hpp: clips x bodies -> retarget -> simulate -> HDF5
// dataset, the loop behind `ptnet simulate` and `ptnet demo`.
//
//   auto clips = ptnet::clips_from_files({"mocap"}, "mocap/clips.csv", {});
//   auto bodies = ptnet::read_bodies_csv("bodies.csv");
//   ptnet::SimulateDatasetOptions opt;      // 80 x 28 mat, 30 fps, seed 0, all cores
//   opt.seed = 7;
//   ptnet::SimulateDatasetSummary s = ptnet::simulate_dataset(clips, bodies, "data.h5", opt);
//
//   auto procedural = ptnet::embedded_clips(5, 2, 8.0, /*seed=*/1);  // no files needed
//
// Every clip is loaded (BVH) or generated (procedural) once, before anything
// is simulated, so a missing or malformed file fails the run at once and no
// output is left. Jobs (clip x body, clip-major) are then retargeted onto the
// body's height, simulated on `threads` threads and written in chunks of
// `chunk_jobs` (chunk i is written, compressed, on its own thread while
// chunk i + 1 is simulated), so memory holds the source clips plus two chunks
// of pressure sequences, whatever the size of the run. Sequence i is
// named "<motion_id>__<body_id>" and seeded with sequence_seed(seed, name):
// the file is byte-identical for any thread count or chunk size.
// Each clip is placed on the mat once, from the source motion (place_motion),
// and every body's copy gets that placement scaled by retarget_scale, so the
// copies of one motion differ by body scale, not by where they lie.
// Sequences on bodies with role "original" (the test bodies) are also read
// by the sensor with a second seed, floor_seed(seed, name), into
// /floor/<name>: the noise floor that `ptnet evaluate` reports.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"

namespace ptnet {

// One motion to simulate: a BVH file (path non-empty) or a procedural clip.
struct ClipSource {
  std::string path;              // BVH file; empty for procedural
  MotionOptions motion;          // how to read the BVH (units, up axis, fps)
  GenerateOptions procedural;    // used when path is empty
  SequenceMeta meta;             // motion_id, performer, category, take, source
                                 // (name and body_id are filled per body)
  // Only frames [first_frame, end_frame) of the clip at the dataset's frame
  // rate (end_frame 0: to the end), cut after loading (load_clip).
  int first_frame = 0, end_frame = 0;
  // Played `speed` times as fast: loaded (or generated) at fps / speed and
  // played at fps, so the body moves faster or slower and is simulated anew
  // (its pressure is the changed motion's, not warped maps). clips_at_speeds.
  double speed = 1;
};

// Allowed playback speeds of a clip (ClipSource::speed).
inline constexpr Range kClipSpeedRange{0.25, 4};
// A clip played at the slowest speed into the fastest dataset is read at
// kFpsRange.hi / kClipSpeedRange.lo: the motion reader must take that rate.
static_assert(kFpsRange.hi / kClipSpeedRange.lo <= kReadFpsRange.hi, "kReadFpsRange too narrow for slow clips");

// Every clip at every speed of `speeds`, clip-major: time-scale augmentation
// of a training set. A clip at speed s != 1 is motion_id "<id>_x<s>" (e.g.
// "06_01_x0.8") with source "<source> x<s>"; at s = 1 it is the clip as it
// was. Throws Error for no speeds, a repeated speed, or one outside
// kClipSpeedRange.
std::vector<ClipSource> clips_at_speeds(const std::vector<ClipSource>& clips, const std::vector<double>& speeds);

// One row of a clips CSV (docs/formats.md): columns file, subject, category,
// take (required); metres_per_unit, up, activity, and for marker files
// marker_map and static, used when present; other columns
// (trial, rig, fps, frames) ignored. `file` is relative to the CSV's folder.
struct ClipRow {
  std::string file;      // resolved path
  std::string subject;   // -> performer
  std::string category;  // walking | rom | freestyle | acting
  int take = 1;
  double metres_per_unit = 0;  // 0: not given
  std::string up;              // "" : not given
  std::string activity;        // fine activity label, lower case ("" : no activity column)
  std::string marker_map;      // .trc files: a shipped map's name or a map file (resolved path); "" : chosen
  std::string static_markers;  // .trc files: the static trial (resolved path); "" : none
  long line = 0;               // line in the CSV, for messages
};

// Reads and validates a clips CSV: "clips.csv:3: expected take as a
// positive integer, found 'x'"; a row whose file does not exist is
// "clips.csv:5: clip file 'missing.bvh' not found".
std::vector<ClipRow> read_clips_csv(const std::string& path);

// The clips of BVH `inputs` (files, or folders searched recursively for
// *.bvh, sorted by path). With `clips_csv`, every input must be listed there
// (error naming the first that is not) and its row supplies the metadata;
// with no inputs, every row of the CSV is a clip. Without it: motion_id =
// the file stem, performer = the parent folder's name, category from the
// name (its stem containing walk, rom/range/exercise, dance/freestyle or
// act(ing); else "" and guessed from the motion when loaded), take 1. `defaults` gives units, up axis and fps for files the CSV
// does not describe. Throws Error for a missing input, an empty folder, or
// two clips with the same motion_id.
std::vector<ClipSource> clips_from_files(const std::vector<std::string>& inputs,
                                         const std::string& clips_csv, const MotionOptions& defaults);

// The procedural clips of `ptnet demo`: performers x 4 categories x takes,
// `seconds` long at `fps`, motion_id "p<P>_<category>_t<take>", performer
// "P<P>", source "procedural:<motion_id>".
std::vector<ClipSource> embedded_clips(int performers, int takes, double seconds, std::uint64_t seed,
                                       double fps = kFps);

// The size of the embedded corpus, `ptnet demo`'s and `ptnet simulate
// --embedded`'s default (embedded_clips).
struct EmbeddedCorpus {
  int performers = 5;   // procedural performers
  int takes = 2;        // takes per performer and category
  double seconds = 8;   // seconds per clip
};

// The sizes embedded_clips accepts (demo and simulate's options read them too).
struct EmbeddedCorpusRanges {
  Range performers{1, 100}, takes{1, 10}, seconds{1, 600};
};
inline constexpr EmbeddedCorpusRanges kEmbeddedCorpusRanges;

// Loads (BVH) or generates (procedural, at the performer's own height) one
// clip at `fps`, cut to its frame span. Throws Error naming the file (or a
// span beyond the clip's frames).
Motion load_clip(const ClipSource& clip, double fps);

struct SimulateDatasetOptions {
  SimOptions sim;                 // mat, placement, sensor; sim.seed is replaced per sequence
  double fps = kFps;              // motions are resampled to this rate
  std::uint64_t seed = 0;         // run seed: sequence_seed(seed, name) per sequence
  int threads = 0;                // 0: hardware concurrency
  int chunk_jobs = 0;             // jobs per chunk; 0: 4 on one thread, else 8 x threads (at least 16)
  bool force = false;             // overwrite an existing output
  bool noise_floor = true;        // /floor/<name> for sequences on original bodies
  int compression = kDefaultCompression;  // deflate level 0-9 of the sequences (DatasetInfo::compression)
  std::string generator = "ptnet simulate";
  std::string config_json;        // "" : built from the options
  // Shard `shard_index` of `shard_count` (ptnet simulate --shard K/N): the
  // K-th contiguous block of the clip x body job list (jobs [J K / N,
  // J (K + 1) / N)); every clip is still loaded and checked. The config gets
  // "shard": "K/N"; `ptnet merge` of the N shards (merge_datasets, data.hpp)
  // gives the unsharded file's sequences, attributes and bodies.
  int shard_index = 0;
  int shard_count = 1;
  // Each sequence's simulated ground reaction (force_table: total and per
  // foot, N, BW, CoP along the foot) as `forces_dir`/<name>.<forces_format>
  // (OpenSim storage or CSV), checked before any work (not the dataset's
  // path, no input replaced) and appearing with the dataset; "": none.
  // Simulating with forces traces every frame: slower.
  std::string forces_dir;
  TableFormat forces_format = TableFormat::mot;
  // Counts as work completes: {"load", done, total, "clips"}, then
  // {"simulate", done, total, "sequences"}. Calls are serialised but may come
  // from worker threads.
  ProgressFn progress;
};

struct SimulateDatasetSummary {
  int clips = 0, bodies = 0, sequences = 0;
  long long frames = 0;        // simulated frames, all sequences
  double seconds = 0;          // wall time of the whole run
  std::vector<std::string> categories;  // category of each clip, after guessing
};

// Simulates every clip on every body and writes the dataset (docs/formats.md)
// to `out_path` atomically (nothing is left on error). Throws Error.
SimulateDatasetSummary simulate_dataset(const std::vector<ClipSource>& clips,
                                        const std::vector<BodySpec>& bodies, const std::string& out_path,
                                        const SimulateDatasetOptions& options);

}  // namespace ptnet
