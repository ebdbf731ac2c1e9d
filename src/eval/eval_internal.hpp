// eval/eval_internal.hpp (private to the eval stage; tests include it as
// "eval/eval_internal.hpp"): the steps of run_evaluation (ptnet/eval.hpp):
// metrics.csv and the group means, the paper's test pairs evaluated, the
// report folder.
#pragma once

#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/pressure.hpp"
#include "ptnet/progress.hpp"

namespace ptnet {
class Dataset;

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

// ------------------------------------------------------------ the protocol

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

// ---------------------------------------------------------------- the report

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

}  // namespace ptnet
