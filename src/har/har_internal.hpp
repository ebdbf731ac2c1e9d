// har/har_internal.hpp (private to the har stage; tests and benchmarks
// include it as "har/har_internal.hpp"): the building blocks of
// validate_har and the HAR benchmark (ptnet/har.hpp, ptnet/har_bench.hpp).
//
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
// Dimension legend: N windows, T = 30 frames per window, H x W = rows x cols
// mat cells (80 x 28), F hand-made features, K PCA components, C classes.
// Pressure in kPa everywhere.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/har.hpp"
#include "ptnet/pressure.hpp"

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

// Bodies like the paper's (half female 165 +- 15 cm, 65 +- 10 kg; half male
// 175 +- 15 cm, 75 +- 10 kg, Gaussian, clamped to valid ranges), ids syn1...
std::vector<BodySpec> sample_paper_bodies(int count, std::uint64_t seed);

// The subject (body) id a token names: a body whose id equals the token, or
// "s<token>" / "subject<token>". Throws Error listing the dataset's bodies
// when none matches.
std::string resolve_subject(const Dataset& data, const std::string& token);

// One line on the pseudo labels: PCA, bandwidth (and how it was chosen),
// clusters, silhouette.
std::string pseudo_label_summary(const HarResult& result);
// A training source as Table 3 names it: "Real", "Synthetic", "Real+Synthetic".
std::string source_title(const std::string& source);

}  // namespace ptnet::har
