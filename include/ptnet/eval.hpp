// ptnet/eval.hpp: metrics of transferred pressure sequences against ground
// truth, and the paper's Table 2 (per category, seen / unseen, beside the
// naive baselines).
//
//   ptnet::SequenceMetrics m = ptnet::compare(predicted, truth, {});
//   std::cout << m.rmse_kpa << " " << m.binary_r2 << "\n";
//
//   std::vector<ptnet::EvalRow> rows = ...;      // one per pair x method
//   std::cout << ptnet::format_table(rows);      // Markdown, paper layout
//
// Definitions (docs/results.md repeats them):
//  - RMSE (kPa) over all cells and frames.
//  - Binary R^2: both maps binarised (cell > threshold, default 0.5 kPa -> 1),
//    then 1 - SS_res / SS_tot with SS_tot taken about the ground truth's mean.
//    When the ground truth is constant (SS_tot = 0) the score is 1 if the
//    binarised maps are identical and 0 otherwise: never NaN.
//  - Centre-of-pressure error (cm): mean distance between the two maps' centres
//    of pressure over frames where both carry load (NaN-free: 0 frames -> 0,
//    and cop_frames = 0 says so).
//  - Total-force error (%): |sum(pred) - sum(truth)| / sum(truth) * 100 over the
//    whole sequence (0 when both are empty, 100 when only truth is empty).
//  - Contact IoU: binarised maps, |A and B| / |A or B| over all cells and frames
//    (1 when both are empty).
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model_config.hpp"
#include "ptnet/pressure.hpp"
#include "ptnet/progress.hpp"

namespace ptnet {

// The binarisation thresholds the metrics accept: any finite kPa >= 0 (the
// check of binary_r2 and contact_iou, of EvaluationRun and of the CLI).
inline constexpr Range kThresholdKpaRange{0, HUGE_VAL};

struct MetricOptions {
  double threshold_kpa = kContactKpa;  // binarisation threshold for binary R^2 and IoU
};

struct SequenceMetrics {
  double rmse_kpa = 0;
  double binary_r2 = 0;
  double cop_error_cm = 0;
  int cop_frames = 0;  // frames where both maps carry load
  double force_error_pct = 0;
  double contact_iou = 0;
};

// Raw metrics on flat arrays of equal length n (kPa). A NaN or infinity in
// either is an Error ("rmse: predicted: non-finite value (NaN or Inf) at
// index 5"), never a NaN metric.
double rmse(const float* predicted, const float* truth, std::size_t n);
double binary_r2(const float* predicted, const float* truth, std::size_t n, double threshold_kpa);
double contact_iou(const float* predicted, const float* truth, std::size_t n,
                   double threshold_kpa);

// All metrics of two sequences of the same shape (throws Error otherwise).
SequenceMetrics compare(const PressureSequence& predicted, const PressureSequence& truth,
                        const MetricOptions& options);

// Naive baselines of the paper: the source unchanged, and the source scaled by
// the target/source weight ratio.
PressureSequence copy_baseline(const PressureSequence& source);
PressureSequence weight_ratio_baseline(const PressureSequence& source, double source_weight_kg,
                                       double target_weight_kg);
// A third, geometric baseline (ours): the source zoomed by the height ratio
// about the mat centre and scaled by the weight ratio over the area ratio
// (zoom_about_centre in pressure.hpp) -- what body scale alone explains.
PressureSequence body_scale_baseline(const PressureSequence& source, const BodySpec& source_body,
                                     const BodySpec& target_body);

// One evaluated (source -> target) pair on one motion, for one method.
struct EvalRow {
  std::string method;    // "model", "model_raw", "copy", "weight_ratio", "body_scale", "floor", "floor"
  std::string motion_id;
  std::string category;  // walking | rom | freestyle | acting
  int take = 1;          // 1 = seen motion, 2 = unseen
  std::string source_sequence, target_sequence;
  std::string source_body, target_body;
  int frames = 0;
  SequenceMetrics metrics;
};

// Markdown table in the layout of the paper's Table 2: rows per category
// (seen, then unseen) and their average; columns RMSE and binary R^2 of each
// method, then CoP error, force error and IoU of the model. Category and
// average values are means over rows (pairs) of that group. The noise floor
// ("floor") always has its columns: "n/a" where no row measured it, with a
// line under the table saying why.
std::string format_table(const std::vector<EvalRow>& rows);
// The line format_table prints under a table without floor rows.
inline constexpr const char* kNoFloorNote =
    "Noise floor n/a: the dataset holds no second-seed copies of its test sequences (/floor); "
    "re-simulate it with `ptnet simulate` or `ptnet demo` (without --no-floor) to measure it.";

// metrics.csv: one row per pair, sequence and method; read back exactly.
std::string format_metrics_csv(const std::vector<EvalRow>& rows);
std::vector<EvalRow> parse_metrics_csv(const std::string& text, const std::string& source);

// Group means as printed by format_table, for JSON output and tests.
struct GroupSummary {
  std::string method, group;  // group: category name or "average"
  bool seen = true;
  int rows = 0;
  SequenceMetrics mean;
};
std::vector<GroupSummary> summarise(const std::vector<EvalRow>& rows);

}  // namespace ptnet

// ------------------------------------------------------------ the protocol

namespace ptnet {
class Dataset;

// The model under test: source sequence and attributes -> sequence for target.
using TransferFn = std::function<PressureSequence(
    const PressureSequence& source, const BodySpec& source_body, const BodySpec& target_body)>;

struct EvaluateOptions {
  MetricOptions metrics;
  // A count after each pair: {"evaluate", done, total, "pairs"}.
  ProgressFn progress;
  // > 0: the model function returns its raw output, evaluated as "model_raw",
  // and "model" is that output with cells below this threshold (kPa) set to 0
  // (the model's fitted contact threshold): both from one transfer.
  double model_threshold_kpa = 0;
};

// One test pair: the same motion on two different `original` bodies.
struct TestPair {
  std::string motion_id, category;
  int take = 1;
  std::string source_sequence, target_sequence;
};

// A test pair read from the dataset, both sequences cut to their common
// length (same motion, same frame range), with the two bodies.
struct PairData {
  PressureSequence source, truth;
  BodySpec source_body, target_body;
};
PairData load_pair(const Dataset& dataset, const TestPair& pair);

// All ordered pairs of two different original bodies on the same motion, in
// a deterministic order (by motion, then source, then target).
std::vector<TestPair> test_pairs(const Dataset& dataset);

// Evaluates every test pair with the model and the three baselines: four
// EvalRows per pair (methods "model", "copy", "weight_ratio", "body_scale"),
// and a fifth, "floor", when the target sequence has a noise-floor copy
// (/floor/<name>: the truth simulated again with another sensor seed,
// compared with the truth; simulate_dataset writes them for original bodies).
// Throws Error if the dataset has no test pairs (it needs >= 2 original bodies).
std::vector<EvalRow> evaluate_pairs(const Dataset& dataset, const TransferFn& model,
                                    const EvaluateOptions& options);

}  // namespace ptnet

// ---------------------------------------------------------------- the report

namespace ptnet {

struct ReportOptions {
  std::string out_dir = "report";  // created if missing
  bool force = false;              // overwrite existing report files
  int frames_per_category = 5;     // frames in each qualitative_<category>.png
  double threshold_kpa = kContactKpa;  // recorded in metrics.json
  std::string model_dir;           // the model's history.csv and config.json on the page ("": none)
  std::string warning;             // about the model (EvaluationResult::warning), atop the page and in
                                   // metrics.json ("warning"); "": none
};

// Writes into out_dir (each file atomically): metrics.csv (one row per pair,
// sequence and method), metrics.json (group means in the Table 2 layout, the
// paper's figures beside them, settings), per category qualitative_<category>.png
// (rows source / ground truth / transferred / |error|) and .gif, worst_<n>.png
// (the 5 pairs with the highest model RMSE), and index.html: one offline page
// with Table 2 (every method in the rows beside the paper's figures), SVG bar
// charts (chart_*.svg), the figures, and the training curve
// (training_curve.svg) and config of options.model_dir. The category figures
// use one seen pair per category (the first in test_pairs order); every figure
// is transferred again with `model`. Returns the paths written.
std::vector<std::string> write_report(const Dataset& dataset, const std::vector<EvalRow>& rows,
                                      const TransferFn& model, const ReportOptions& options);

// ------------------------------------------------- the whole evaluate step

// The paper's averages (kPaperTable2, paper.hpp) as one line under a table:
// "Paper (Table 2): seen RMSE 8.88, binary R^2 0.79; unseen RMSE 12.82, ...".
std::string paper_table2_line();

// `ptnet evaluate` as a function (the CLI and `ptnet demo` call it): the
// trained model in model_dir (ptnet::Transfer) on every test pair of the
// dataset, the table, and the report in out_dir.
struct EvaluationRun {
  std::string model_dir, data_path, out_dir = "report";
  double threshold_kpa = kContactKpa;  // binarisation for binary R^2 and IoU
  int stride = 5;                      // frames between transfer windows
  int threads = 0;                     // Torch threads (0: default)
  bool raw = false;                    // skip the model's fitted contact threshold
  bool force = false;                  // overwrite report files
  ProgressFn progress;                 // EvaluateOptions::progress
};
struct EvaluationResult {
  std::vector<EvalRow> rows;
  std::string table;                   // format_table(rows)
  std::vector<std::string> written;    // report files
  std::string page;                    // the report page, out_dir/index.html
  // baseline_warning of the model's validation metrics (config.json): ""
  // for a model that beat the all-zero and copy baselines when trained.
  std::string warning;
};
EvaluationResult run_evaluation(const EvaluationRun& run);

}  // namespace ptnet
