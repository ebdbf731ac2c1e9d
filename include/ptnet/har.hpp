// ptnet/har.hpp: the HAR validation stage (paper section 4.2, Table 3). Does
// transferred pressure data help an activity classifier on held-out subjects?
//
//   // the building blocks
//   Eigen::MatrixXd f = ptnet::har::window_features(windows, mat);   // [N, F]
//   ptnet::har::robust_standardise(f);                               // median/MAD, clipped
//   ptnet::har::Pca pca = ptnet::har::Pca::fit(f, 4);                // standardise + PCA
//   Eigen::MatrixXd z = pca.transform(f);                            // [N, 4]
//   ptnet::har::MeanShiftResult ms = ptnet::har::mean_shift(z, {});  // pseudo labels (bandwidth rule)
//   double ari = ptnet::har::adjusted_rand_index(ms.labels, categories);
//   ptnet::har::WindowClassifier net(shape, ms.clusters(), {});      // small CNN
//   net.train(inputs, ms.labels);
//   auto report = ptnet::har::classification_report(truth, net.predict(test), classes);
//
//   // the whole experiment (what `ptnet validate-har` runs)
//   ptnet::Dataset real = ptnet::Dataset::open("real.h5");
//   ptnet::har::HarResult r = ptnet::har::validate_har(real, transfer_fn, options);
//   std::cout << ptnet::har::format_table(r);
//
// Dimension legend: N windows, T = 30 frames per window, H x W = rows x cols
// mat cells (80 x 28), F hand-made features, K PCA components, C classes.
// Pressure in kPa everywhere.
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

// kWindowFrames and kContactKpa: ptnet/paper.hpp.
inline constexpr int kCentredGridRows = 8;       // centred occupancy grid, blocks along the mat
inline constexpr int kCentredGridCols = 4;       // ... and across
inline constexpr int kCentredBlockRows = 5;      // cells per block along (5 x 2 cm = 10 cm)
inline constexpr int kCentredBlockCols = 4;      // cells per block across (4 x 2 cm = 8 cm)

// ---------------------------------------------------------------- features

// A contiguous set of equally sized windows: values [N, T, H, W] kPa.
struct WindowBatch {
  MatSpec mat;
  int frames = kWindowFrames;  // T
  std::vector<float> kpa;      // [N, T, H, W]
  int count() const {
    const std::size_t per = std::size_t(frames) * mat.cells();
    return per ? int(kpa.size() / per) : 0;
  }
  const float* window(int i) const { return kpa.data() + std::size_t(i) * frames * mat.cells(); }
};

// Names of the features window_feature_vector() returns, in order (F of them).
const std::vector<std::string>& feature_names();

// Pooled pressure statistics of one window [T, H, W] kPa -> [F] (mixed units:
// N, cells, m, m/s, kPa; see feature_names() and docs/har.md). Summaries of
// the total-force time profile, contact area, centre-of-pressure path and
// speed, spatial spread of the load, peak pressure, frame-to-frame change and
// a coarse contact-occupancy grid centred on the window's mean centre of
// pressure (so the position on the mat does not matter).
std::vector<double> window_feature_vector(const float* window, int frames, const MatSpec& mat,
                                          double fps = kFps);

// All windows of a batch -> [N, F].
Eigen::MatrixXd window_features(const WindowBatch& windows, double fps = kFps);

// Divides the body-scaled features (force_mean_n, area_*, peak_*) of each
// window by the median of that feature over its subject's windows, so that
// clusters follow activities rather than bodies. features [N, F], subject [N].
void normalise_per_subject(Eigen::MatrixXd& features, const std::vector<std::string>& subject);

// Robust standardisation, in place: each column of features [N, F] becomes
// (x - median) / (1.4826 MAD), clipped to +-clip (a column with MAD 0 uses
// its standard deviation, a constant column becomes 0). The window features
// are heavy-tailed (peaks, speeds, force ratios): a plain z-score lets a few
// extreme windows set every distance, and mean shift then sees one blob.
void robust_standardise(Eigen::MatrixXd& features, double clip = 3);

// Standardisation (z-score per column; a constant column keeps scale 1) then
// principal components by Eigen::SelfAdjointEigenSolver on the covariance.
struct Pca {
  Eigen::RowVectorXd mean;        // [F]
  Eigen::RowVectorXd scale;       // [F] standard deviations (1 where constant)
  Eigen::MatrixXd components;     // [F, K], columns = unit eigenvectors, largest first
  Eigen::VectorXd variance;       // [K] eigenvalues (variance along each component)
  double explained = 0;           // fraction of the total variance kept

  // Throws Error when X has fewer than 2 rows or k is outside [1, F].
  // Each component's sign is fixed so that its largest-magnitude entry is
  // positive (deterministic output).
  static Pca fit(const Eigen::MatrixXd& x, int k);
  Eigen::MatrixXd transform(const Eigen::MatrixXd& x) const;  // [N, F] -> [N, K]
};

// ---------------------------------------------------------------- mean shift

enum class Kernel { flat, gaussian };

struct MeanShiftOptions {
  double bandwidth = 0;           // > 0: this bandwidth; else the rule below
  // The bandwidth rule: a clustering at estimate_bandwidth(x, q) for each
  // candidate q, the one with the highest silhouette kept (a tie: fewer
  // clusters). One entry: that quantile, no selection (scikit-learn's
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

struct MeanShiftResult {
  double bandwidth = 0;        // the bandwidth used (given or estimated)
  double quantile = 0;         // the rule's chosen quantile (0: bandwidth given)
  double silhouette = -1;      // of the clustering (sampled; -1: a single cluster)
  std::vector<BandwidthCandidate> candidates;  // what the rule tried, in quantile order
  Eigen::MatrixXd modes;       // [C, K], ordered by cluster size, largest first
  std::vector<int> labels;     // [N] cluster of each point, 0..C-1
  std::vector<int> sizes;      // [C] points per cluster
  int seeds = 0;               // how many seeds were climbed
  int clusters() const { return int(modes.rows()); }
};

// The bandwidth estimate: the mean, over the points of a deterministic
// subsample (every ceil(N / max_points)-th row, at most max_points rows), of
// the distance to the k-th nearest other point of that subsample, with
// k = max(1, round(quantile * (m - 1))); scikit-learn's estimate_bandwidth
// without its random subsampling. Throws Error for fewer than 2 points or a
// quantile outside (0, 1]. Returns at least 1e-12 (all points equal).
double estimate_bandwidth(const Eigen::MatrixXd& x, double quantile = 0.3, int max_points = 1000);

// Mean-shift clustering of x [N, K], bandwidth given or chosen by the rule
// (MeanShiftOptions::quantiles). Deterministic; no randomness at all.
MeanShiftResult mean_shift(const Eigen::MatrixXd& x, const MeanShiftOptions& options);

// Index of the nearest mode (Euclidean) for every row of x: [N].
std::vector<int> assign_nearest(const Eigen::MatrixXd& modes, const Eigen::MatrixXd& x);

// ---------------------------------------------------------------- metrics

struct ClassificationReport {
  int classes = 0;
  Eigen::MatrixXi confusion;      // [C, C], row = true class, column = predicted
  std::vector<double> precision;  // [C]
  std::vector<double> recall;     // [C]
  std::vector<double> f1;         // [C]; 0 for a class with tp = 0
  std::vector<int> support;       // [C] true count
  std::vector<bool> present;      // [C] class occurs in truth or prediction
  double macro_f1 = 0;            // mean F1 over present classes (scikit-learn's labels=None)
  double accuracy = 0;
};

// Mean of `v` (0 when empty) and its sample standard deviation (n - 1; 0
// for fewer than 2 values): the spread over seeded runs.
double mean_of(const std::vector<double>& v);
double sd_of(const std::vector<double>& v);

// The column of each row's largest score (the first on a tie): scores
// [N x C] row-major -> [N].
std::vector<int> argmax_rows(const std::vector<float>& scores, int columns);

// Labels must lie in [0, classes); throws Error otherwise or when the sizes
// differ or are empty. A class that never occurs in truth nor prediction
// does not count in the macro average; one that occurs only in one of them
// has F1 = 0 and counts (zero_division = 0).
ClassificationReport classification_report(const std::vector<int>& truth,
                                            const std::vector<int>& predicted, int classes);

// Agreement of a clustering with reference labels (both [N], values >= 0;
// throws Error for unequal lengths, no points or a negative label).
// Purity: the fraction of points in their cluster's majority class.
double cluster_purity(const std::vector<int>& clusters, const std::vector<int>& truth);
// Adjusted Rand index (Hubert & Arabie; scikit-learn's adjusted_rand_score):
// 1 = the same partition, about 0 = chance agreement; symmetric.
double adjusted_rand_index(const std::vector<int>& a, const std::vector<int>& b);
// Mean silhouette of x [N, K] under labels [N] (Euclidean; scikit-learn's
// silhouette_score: a singleton scores 0): near 1 = compact, well separated
// clusters, near 0 = overlapping. Throws Error with fewer than 2 clusters.
double silhouette(const Eigen::MatrixXd& x, const std::vector<int>& labels);

// ---------------------------------------------------------------- classifier

// Classifier input: each window block-averaged over time (T / time_blocks
// frames per block) and over pool x pool cells, then log1p(kPa):
// [N, time_blocks, H / pool, W / pool] (H, W rounded down to a multiple of pool).
struct InputOptions {
  int time_blocks = 6;  // 30 frames -> 6 blocks of 5 frames (the CNN's channels)
  int pool = 4;         // 80 x 28 -> 20 x 7 (8 cm cells; 3x faster than 2 x 2)
};

struct PreparedWindows {
  int channels = 0, rows = 0, cols = 0;
  std::vector<float> values;  // [N, channels, rows, cols], log1p(kPa)
  int count() const {
    const std::size_t per = std::size_t(channels) * rows * cols;
    return per ? int(values.size() / per) : 0;
  }
  void append(const PreparedWindows& other);  // shapes must agree (throws Error)
};

// One window [T, H, W] kPa appended to out (shape set on first use).
void prepare_window(const float* window, int frames, const MatSpec& mat,
                    const InputOptions& options, PreparedWindows& out);
PreparedWindows prepare_windows(const WindowBatch& windows, const InputOptions& options);

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

// Two conv blocks (3x3 conv, BatchNorm, ReLU, 2x2 max pool), adaptive average
// pooling to 4 x 2, FC(hidden), ReLU, dropout 0.2, FC(classes). Trained with
// Adam on cross entropy; same seed, same weights (single-threaded CPU).
class WindowClassifier {
 public:
  WindowClassifier(int channels, int rows, int cols, int classes, const ClassifierOptions& options);
  ~WindowClassifier();
  WindowClassifier(WindowClassifier&&) noexcept;
  WindowClassifier& operator=(WindowClassifier&&) noexcept;

  // labels [N] in [0, classes). Returns the mean training loss of the last epoch.
  double train(const PreparedWindows& inputs, const std::vector<int>& labels);
  std::vector<int> predict(const PreparedWindows& inputs) const;  // [N]
  // Softmax class probabilities [N x C], row-major (predict is their argmax).
  std::vector<float> probabilities(const PreparedWindows& inputs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
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
  std::vector<BodySpec> bodies;  // synthetic target bodies; empty: sample_paper_bodies
  int synthetic_bodies = 3;      // how many to sample when `bodies` is empty (3x the real windows,
                                 // the paper's synthetic:real ratio when fine-tuning)
  std::uint64_t seed = 1;        // body sampling
  bool category_labels = true;   // also train/evaluate on the dataset's category labels
  ProgressFn progress;           // a line {"har", line} per step, may be empty
};

// Bodies like the paper's (half female 165 +- 15 cm, 65 +- 10 kg; half male
// 175 +- 15 cm, 75 +- 10 kg, Gaussian, clamped to valid ranges), ids syn1...
std::vector<BodySpec> sample_paper_bodies(int count, std::uint64_t seed);

// The subject (body) id a token names: a body whose id equals the token, or
// "s<token>" / "subject<token>". Throws Error listing the dataset's bodies
// when none matches.
std::string resolve_subject(const Dataset& data, const std::string& token);

// Resolves and checks the subject lists before any work: both non-empty,
// every token a body (resolve_subject), no subject twice or in both lists,
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
// One line on the pseudo labels: PCA, bandwidth (and how it was chosen),
// clusters, silhouette.
std::string pseudo_label_summary(const HarResult& result);
std::string to_json(const HarResult& result);  // pretty-printed JSON text
// A training source as Table 3 names it: "Real", "Synthetic", "Real+Synthetic".
std::string source_title(const std::string& source);

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
// validate-har's, resolve_subject), so no test subject can reach
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
