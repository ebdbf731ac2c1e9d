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

}  // namespace ptnet

// ------------------------------------------------- the whole evaluate step

namespace ptnet {

// The model under test: source sequence and attributes -> sequence for target.
using TransferFn = std::function<PressureSequence(
    const PressureSequence& source, const BodySpec& source_body, const BodySpec& target_body)>;

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
  ProgressFn progress;                 // after each pair: {"evaluate", done, total, "pairs"}
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
