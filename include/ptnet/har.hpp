// ptnet/har.hpp: the HAR validation stage (paper section 4.2, Table 3). Does
// transferred pressure data help an activity classifier on held-out subjects?
//
//   // what `ptnet validate-har` runs
//   ptnet::Dataset real = ptnet::Dataset::open("real.h5");
//   ptnet::har::HarResult r = ptnet::har::validate_har(real, transfer_fn, options);
//   std::cout << ptnet::har::format_table(r);
//
// The experiment's steps (window features, PCA, mean shift, the classifier,
// the metrics) are private to the stage. Dimension legend: K PCA
// components, C classes. Pressure in kPa everywhere.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/pressure.hpp"
#include "ptnet/progress.hpp"

namespace ptnet {
class Dataset;
}

namespace ptnet::har {

// ---------------------------------------------------------------- mean shift

enum class Kernel { flat, gaussian };

struct MeanShiftOptions {
  double bandwidth = 0;           // > 0: this bandwidth; else the rule below
  // The bandwidth rule: a clustering at the bandwidth estimate of each
  // candidate quantile q (docs/har.md), the one with the highest
  // silhouette kept (a tie: fewer clusters). One entry: that quantile, no selection (scikit-learn's
  // default is the single quantile 0.3, which merges any structure finer
  // than ~30 % of the data: docs/har.md).
  std::vector<double> quantiles{0.05, 0.1, 0.15, 0.2, 0.3};
  int silhouette_points = 2000;   // silhouette on every ceil(N / this)-th point
  Kernel kernel = Kernel::flat;   // flat: mean of points within the bandwidth
  int max_iterations = 300;       // per seed
  double tolerance = 1e-3;        // stop when a mode moves less than tolerance x bandwidth
  bool bin_seeding = true;        // seeds = centres of occupied bandwidth-sized grid bins
  int min_bin_count = 1;          // bins with fewer points give no seed
  double merge_distance = 0.5;    // modes closer than this x bandwidth are one mode
  double min_cluster_fraction = 0.01;  // smaller clusters merge into the nearest larger one
};

// One bandwidth the rule tried.
struct BandwidthCandidate {
  double quantile = 0, bandwidth = 0;
  int clusters = 0;
  double silhouette = -1;  // -1: a single cluster
};

// ---------------------------------------------------------------- metrics

// ---------------------------------------------------------------- classifier

// Classifier input: each window block-averaged over time (T / time_blocks
// frames per block) and over pool x pool cells, then log1p(kPa):
// [N, time_blocks, H / pool, W / pool] (H, W rounded down to a multiple of pool).
struct InputOptions {
  int time_blocks = 6;  // 30 frames -> 6 blocks of 5 frames (the CNN's channels)
  int pool = 4;         // 80 x 28 -> 20 x 7 (8 cm cells; 3x faster than 2 x 2)
};

struct ClassifierOptions {
  int epochs = 10;              // passes over the training set
  int batch_size = 128;         // windows per Adam step
  double learning_rate = 2e-3;  // Adam
  double weight_decay = 1e-4;   // Adam L2
  int conv1 = 16;               // channels of the first conv block
  int conv2 = 32;               // channels of the second conv block
  int hidden = 64;              // width of the hidden fully connected layer
  std::uint64_t seed = 1;       // weights and shuffling
  std::string device = "cpu";   // "cpu", "cuda", "cuda:1"
  // Cross entropy weighted by n / (C x count of the class), so that a rare
  // class weighs as much as a common one (macro F1 scores them equally).
  bool balanced = false;
  int threads = 0;              // torch::set_num_threads when > 0 (0: leave LibTorch's setting)
  // Learning rate annealed along a half cosine from learning_rate to 0 over
  // the epochs (else constant): the last epochs settle instead of jumping.
  bool cosine = false;
};

// ---------------------------------------------------------------- experiment

// Turns a sequence recorded on `source` into the one `target` would give
// (the model's transfer); same frame count and mat.
using TransferFn = std::function<PressureSequence(const PressureSequence& sequence,
                                                  const BodySpec& source,
                                                  const BodySpec& target)>;

struct HarOptions {
  std::vector<std::string> train_subjects{"1", "2", "3"};
  std::vector<std::string> test_subjects{"4", "5"};
  int runs = 10;                 // seeded classifier runs per training source
  int stride = 5;                // frames between window starts (paper: 1)
  int pca_components = 4;        // K
  MeanShiftOptions mean_shift;   // bandwidth <= 0: estimated
  InputOptions input;
  ClassifierOptions classifier;  // seed of run r = classifier.seed + r
  std::vector<BodySpec> bodies;  // synthetic target bodies; empty: sampled like the paper's
  int synthetic_bodies = 3;      // how many to sample when `bodies` is empty (3x the real windows,
                                 // the paper's synthetic:real ratio when fine-tuning)
  std::uint64_t seed = 1;        // body sampling
  bool category_labels = true;   // also train/evaluate on the dataset's category labels
  ProgressFn progress;           // a line {"har", line} per step, may be empty
};

// Resolves and checks the subject lists before any work: both non-empty,
// every token a body (its id, or "s<token>" / "subject<token>"), no subject twice or in both lists,
// every subject with a sequence of at least 30 frames. Returns the body ids
// {train, test}; throws Error naming the dataset otherwise.
std::pair<std::vector<std::string>, std::vector<std::string>> check_subjects(
    const Dataset& data, const HarOptions& options);

struct SourceResult {
  std::string source;                 // "real", "synthetic", "real+synthetic"
  int train_windows = 0;
  std::vector<double> macro_f1;       // [runs]
  std::vector<double> accuracy;       // [runs]
  double macro_f1_mean = 0, macro_f1_std = 0, accuracy_mean = 0;
  std::vector<double> class_f1_mean;  // [C] over runs
  Eigen::MatrixXi confusion;          // [C, C] summed over runs
  // The same against the dataset's category labels (empty when not run).
  std::vector<double> category_macro_f1;
  double category_macro_f1_mean = 0, category_macro_f1_std = 0;
  Eigen::MatrixXi category_confusion;
};

struct HarResult {
  std::string dataset;
  std::vector<std::string> train_subjects, test_subjects;
  std::vector<BodySpec> synthetic_bodies;
  int runs = 0, stride = 0;
  int train_windows = 0, test_windows = 0;
  int pca_components = 0;
  double pca_explained = 0;
  double bandwidth = 0;
  bool bandwidth_estimated = true;
  double bandwidth_quantile = 0;                    // the rule's choice (0: given)
  std::vector<BandwidthCandidate> bandwidth_candidates;  // what the rule tried
  double silhouette = -1;                           // of the pseudo labels, in PCA space
  int clusters = 0;
  std::vector<int> cluster_sizes;                   // [C] over all real windows
  // [C] per cluster, the features furthest from the median window: (name,
  // mean robust z over the cluster's windows), largest |z| first (4 each).
  std::vector<std::vector<std::pair<std::string, double>>> cluster_features;
  std::vector<std::string> categories;              // category label names (sorted)
  Eigen::MatrixXi cluster_vs_category;              // [C, categories] window counts
  double cluster_purity = 0;                        // majority-category fraction
  double cluster_ari = 0;                           // adjusted Rand index against categories
  std::vector<SourceResult> sources;                // real, synthetic, real+synthetic
  double seconds = 0;
};

// The experiment (docs/har.md): windows of the real dataset's train and test
// subjects; features -> standardise + PCA -> mean shift fitted on all real
// windows -> pseudo labels; synthetic windows = every train-subject sequence
// transferred onto each synthetic body, labelled with its source window's
// pseudo label; a classifier per source and run, evaluated on the test
// subjects' real windows. Throws Error for empty/overlapping subject lists,
// unknown subjects, or subjects without a full window.
HarResult validate_har(const Dataset& real, const TransferFn& transfer, const HarOptions& options);

// Table 3's layout (one row of macro F1 mean +- std per label kind, one
// column per training source) plus accuracy and per-class F1.
std::string format_table(const HarResult& result);
std::string to_json(const HarResult& result);  // pretty-printed JSON text

// ---------------------------------------------------------------- stand-in

// The stand-in for real recordings (no real pressure-mat data is available
// to this project; docs/har.md): five subjects s1..s5, each a distinct body
// (sex alternating, performer's own height, weight from a seeded BMI)
// performing its own procedural motions (performers 11..15, never used for
// training data) in every category, simulated with a sensor profile unlike
// the training data's: twice the crosstalk, three times the noise, a fixed
// per-cell gain spread (log-normal) and dead cells.
// With `mocap` set: one subject s<CMU subject> per CMU subject of the
// folder's clips.csv instead, each on its own sampled body (sex alternating
// in subject order, stature female 163 +- 6.5 / male 177 +- 7 cm, weight from
// the BMI), performing that subject's clips retargeted onto it; the same
// simulation and degraded sensor.
struct StandinOptions {
  std::string mocap;              // folder with clips.csv + BVH files; empty: procedural
  int subjects = 5;               // s1..sN (procedural only)
  int first_performer = 11;       // procedural performer of s1 (s2 = +1, ...)
  double seconds = 20;            // per category clip (procedural only)
  int takes = 1;                  // clips per category and subject (procedural only)
  double crosstalk = 0.08;        // per neighbour (training default 0.04)
  double noise_sd_kpa = 0.6;      // (training default 0.2)
  double gain_sd = 0.15;          // sigma of the per-cell log-normal gain
  double dead_fraction = 0.01;    // cells that always read 0
  // fixed: a physical 1.6 m mat (the procedural motions stay on it); follow:
  // the mat follows the body (real clips walk, dribble and leap off a fixed
  // mat: docs/har.md)
  std::string placement = "fixed";
  std::uint64_t seed = 1;
  int threads = 0;                // simulation threads (0: all cores)
  ProgressFn progress;            // a line {"standin", line} per step, may be empty
};

// Writes the stand-in dataset to `path` (atomically; refuses to overwrite
// without force). Bodies have role "original"; sequences carry performer,
// category and take; the root config attribute says "stand-in".
void write_standin(const std::string& path, const StandinOptions& options, bool force);

// ---------------------------------------------------------------- import

// Real recordings into the dataset format (docs/har.md, "Your own
// recordings"). The manifest is a CSV with the header
//   subject,sex,height_cm,weight_kg,file[,category]
// one line per recording; a subject's attributes must agree on all its
// lines; `file` (relative to the manifest's folder) is a float32 .npy
// [T, rows, cols] or a .csv with one frame per line (rows x cols values,
// row-major, kPa). Each subject becomes a body (role "original"), each line
// a sequence "<file stem>__<subject>" (motion_id = file stem, performer =
// subject, take 1). Throws Error "FILE:LINE: expected X, found Y" for a bad
// manifest line.
struct ImportOptions {
  MatSpec mat;      // the recordings' mat
  double fps = kFps;  // their frame rate
};
void import_recordings(const std::string& manifest, const std::string& out,
                       const ImportOptions& options, bool force);

// The fine-tuning set for `ptnet train --init model/ --identity-pairs`
// (paper 4.2: the model is fine-tuned on the training subjects' real
// recordings): only the named subjects of `real` (tokens resolved like
// validate-har's), so no test subject can reach
// fine-tuning; their bodies get role "retargeted" and every sequence take 1,
// what the training protocol trains on. Each recording is on one body only,
// hence --identity-pairs (source = target pairs). Throws Error for an empty
// or repeated subject list or an unknown subject.
void write_finetune_set(const std::string& real, const std::vector<std::string>& subjects,
                        const std::string& out, bool force);

// Confusion matrices side by side, one per training source, rows normalised
// (white = 0, dark blue = 1), with class indices; written atomically.
void write_confusion_png(const std::string& path, const HarResult& result, bool force);

// har/index.html, one offline page: Table 3 (macro F1 mean +- sample std over
// runs per training source, per-run values, accuracy), a bar chart with the
// spread (f1.svg), the confusion matrices as shaded tables (rows = true label,
// row-normalised shading, summed counts) beside confusion.png (written by
// write_confusion_png into the same folder), per-class F1 and the settings.
// Writes index.html and f1.svg into out_dir; returns the paths written.
std::vector<std::string> write_html_report(const std::string& out_dir, const HarResult& result, bool force);

}  // namespace ptnet::har
