// ptnet/train.hpp: training PressureTransferNet (no Torch in this header).
//
//   auto data = ptnet::open_dataset_source("data.h5");      // or any PressureSource
//   ptnet::TrainOptions opt = ptnet::TrainOptions::from_preset("fast");
//   opt.seed = 7;
//   ptnet::TrainResult r = ptnet::train(*data, "model/", opt);  // config.json, model.pt, ...
//
// Protocol (the paper's): train on bodies with role "retargeted" and take-1
// motions only; "original" bodies and take-2 motions are never read. A pair
// is the same motion_id on two different bodies (both orders), over the
// frame range both have. Instances are windows of `window` frames at
// `stride`, indexed lazily as (pair, start frame). The 9:1 train/validation
// split is per motion by time: a contiguous block of ~10 % of each motion's
// window starts (position drawn from the seed) is validation, and training
// windows that would overlap a validation window are dropped, so no frame is
// in both sets.
//
// Dimension legend: T window frames, H x W mat rows x cols, A = 3 attributes.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model_config.hpp"
#include "ptnet/pressure.hpp"
#include "ptnet/progress.hpp"

namespace ptnet {

// ------------------------------------------------------------ data sources

// Where training frames come from: the dataset file (open_dataset_source) or
// any other implementation (the tests keep sequences in memory:
// tests/support/memory_source.hpp).
class PressureSource {
 public:
  virtual ~PressureSource() = default;
  virtual std::string path() const = 0;  // names the source in messages
  virtual MatSpec mat() const = 0;
  virtual double fps() const = 0;
  virtual const std::vector<BodySpec>& bodies() const = 0;
  virtual const std::vector<SequenceMeta>& sequences() const = 0;  // frames filled in
  // Frames [start, start + count) of sequence `name` into out[count, H, W], kPa.
  virtual void read(const std::string& name, int start, int count, float* out) const = 0;

  const BodySpec& body(const std::string& id) const;          // throws Error if absent
  const SequenceMeta& sequence(const std::string& name) const;  // throws Error if absent
  PressureSequence read_all(const std::string& name) const;    // [T, H, W] kPa
};

// The HDF5 dataset file (ptnet::Dataset) as a source. Throws Error if the
// binary was built without the data stage.
std::unique_ptr<PressureSource> open_dataset_source(const std::string& path);

// The lazy window index, the normalisation fit and the sequence cache behind
// train() are internals: src/train/window_index.hpp.

// ---------------------------------------------------------------- training

enum class Loss { mse, mse_force };  // mse_force adds a per-frame total-force term
Loss parse_loss(const std::string& text);  // "mse" | "mse+force"; throws Error
const char* loss_name(Loss loss);

// What a front end (`ptnet train`'s flags, Python's train()) changes on top
// of a preset; an unset field keeps the preset's value. TrainOptions::
// from_preset(name, overrides) applies them with the rules that tie them
// together: the architecture first (set_arch), then the window, and a
// contact head exactly when contact_weight > 0.
struct TrainOverrides {
  std::optional<int> epochs, batch, micro_batch, lr_halve_every, patience, threads, stride, crop_rows;
  std::optional<double> lr, cache_mb, contact_weight;
  std::optional<std::uint64_t> seed;
  std::optional<std::int64_t> samples_per_epoch, val_samples;
  std::optional<Arch> arch;
  std::optional<Align> align;
  std::optional<std::array<int, 3>> channels;
  std::optional<int> hidden, latent, window, context;
  std::optional<bool> mirror;
  std::optional<Loss> loss;
};

struct TrainOptions {
  std::string preset = "paper";     // paper | fast | full (set by from_preset())
  ModelConfig model;                // window, rows and cols are taken from the data
  int epochs = 500;                 // maximum epochs
  int batch = 1028;                 // windows per optimiser step
  int micro_batch = 64;             // windows per forward/backward pass; gradients of a batch's
                                    // micro-batches are accumulated (bounds memory; BatchNorm
                                    // statistics are per micro-batch). 16 is faster per window
                                    // but learns worse: corpus fast preset validation
                                    // RMSE 3.149 vs 2.851 kPa (docs/model.md "Speed")
  double lr = 0.01;                 // Adam initial learning rate
  int lr_halve_every = 20;          // epochs between halvings of the learning rate
  int patience = 50;                // early stop after this many epochs without val improvement
  std::uint64_t seed = 1;           // weights, sampling and split
  int threads = 2;                  // torch::set_num_threads (measured: bench/bench_model.cpp)
  std::string device = "cpu";       // cpu | cuda
  int stride = 1;                   // frames between window starts
  std::int64_t samples_per_epoch = 0;  // training windows drawn per epoch (0 = all)
  std::int64_t val_samples = 0;     // validation windows, evenly spaced (0 = all)
  Loss loss = Loss::mse;
  double force_weight = 0.1;        // weight of the total-force term (Loss::mse_force)
  double contact_weight = 0;        // weight of the contact head's cross-entropy (model.contact)
  double cache_mb = 1024;           // whole-sequence cache budget
  int crop_rows = 0;                // Arch::frame: train on this many mat rows around the window's
                                    // pressure (0 = the whole mat); validation uses the whole mat.
                                    // The window networks (fully connected layers) ignore it.
  // Every second window of a micro-batch is mirrored left-right
  // (input and truth, through the mat's long axis: a mirrored motion on the
  // same, symmetric bodies), and after training ModelConfig::mirror (mirror
  // averaging at inference) is kept if it lowers the validation RMSE.
  bool mirror = false;
  bool fit_contact_threshold = true;  // after training, fit the output activation threshold
  bool resume = false;              // continue from OUT/checkpoint.pt
  std::string init;                 // start from this model folder's weights
  bool identity_pairs = false;      // WindowOptions::identity_pairs (fine-tuning on recordings)
  bool force = false;               // overwrite an existing model folder
  // A model no better than the all-zero or copy baseline on validation
  // (baseline_warning, model_config.hpp) is an Error, after the folder is
  // written (it is kept), instead of TrainResult::warning.
  bool strict = false;
  // Data-parallel training over `world_size` processes (docs/distributed.md):
  // every optimiser step's micro-batches are dealt round-robin to the ranks
  // (micro-batch m to rank m % world_size), gradients and BatchNorm
  // statistics are summed with a Gloo all-reduce, so N ranks take the same
  // steps as one process with the same --batch. Rank 0 alone writes the
  // model folder; with --resume every rank reads it (a shared filesystem).
  int world_size = 1;
  int rank = 0;                     // 0 .. world_size - 1
  std::string rendezvous;           // tcp://HOST:PORT (rank 0 listens) or file://PATH
  double dist_timeout_s = 60;       // bound on joining and on every all-reduce
  // tcp://: the run's secret, the same on every rank (16-256 printable
  // characters; `ptnet train` reads it from PTNET_DIST_TOKEN, --nproc makes
  // one): rank 0's store serves no connection without it. Never written to
  // the model folder.
  std::string dist_token;
  // Reports (the library prints nothing itself): after each optimiser step
  // a count {what "train", done/total training windows of the epoch, unit
  // "windows", step/steps = epoch (1-based)/epochs}; the setup, each epoch
  // ("[epoch 3/15] train 0.0412 val 0.0398 lr 5.0e-3 1.9 s") and the final
  // metrics as lines.
  ProgressFn progress;

  // "paper": the paper's network and schedule (the defaults above). "fast":
  // ours, for two CPU cores; "full": the fast network trained longer. The
  // values are set in one place, from_preset() (src/train/train_options.cpp);
  // summary() describes them (`ptnet train --help`).
  static TrainOptions from_preset(const std::string& name);  // throws Error if unknown
  // The preset with `overrides` applied (TrainOverrides).
  static TrainOptions from_preset(const std::string& name, const TrainOverrides& overrides);
  // Switches the architecture. A window network (faithful, skip, residual)
  // takes the paper's 30-frame window and has no contact head (both are the
  // frame network's); the frame network keeps the preset's window and head.
  void set_arch(Arch arch);
  // One line naming the architecture and schedule ("frame 16/32/48 on zoom-aligned
  // input, window 1, batch 64, lr 0.0015 halved every 4 epochs, ..."): the
  // presets are described from their values, never by hand.
  std::string summary() const;
};

// The values each option accepts (the model's: ModelConfigRanges): the
// library's check_options() and `ptnet train`'s validators read them.
struct TrainOptionsRanges {
  Range epochs{1, 1e6}, batch{1, 1 << 20}, micro_batch{1, 1 << 20}, lr{0, 10, true}, lr_halve_every{1, 1e6};
  Range patience{1, 1e6}, stride{1, 1e5}, samples_per_epoch{0, 0x1p40}, val_samples{0, 0x1p40};
  Range crop_rows{0, 1 << 24}, contact_weight{0, 1e6}, cache_mb{0, 1e7, true}, dist_timeout_s{0.1, 86400};
};
inline constexpr TrainOptionsRanges kTrainOptionsRanges{};

// Throws Error for options train() cannot run with, naming the field
// ("epochs: 0 is not in [1, 1e+06]", "resume and init exclude each other",
// "contact_weight: 0.1 trains a contact head, which model.contact leaves out").
// train() calls it first; a front end may call it before opening the data.
void check_options(const TrainOptions& options);

struct TrainResult {
  int epochs_run = 0;         // epochs completed (including resumed ones)
  int best_epoch = 0;         // 1-based
  double best_val_loss = 0;   // normalised MSE
  double first_val_loss = 0;  // after epoch 1
  double val_rmse_kpa = 0;    // of the best weights on the validation windows
  bool stopped_early = false;
  double seconds = 0;
  // baseline_warning of the final metrics: "" for a model that beats the
  // all-zero and the copy baseline on validation, else the line saying it
  // does not (front ends show it; TrainOptions::strict makes it an Error).
  std::string warning;
  // Distributed runs: this rank's all-reduces (count, payload bytes, time).
  long long allreduce_calls = 0, allreduce_bytes = 0;
  double allreduce_seconds = 0;
};

// Trains into `out_dir` (created; an existing non-empty folder needs force or
// resume). Throws Error on bad input, a non-finite loss (the last good
// checkpoint is kept), or a dataset without training pairs.
TrainResult train(const PressureSource& source, const std::string& out_dir, const TrainOptions& options);

}  // namespace ptnet
