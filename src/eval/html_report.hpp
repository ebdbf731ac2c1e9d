// Internal to the eval stage: the report page (index.html) that write_report
// (report.cpp) writes beside its figures.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/eval_internal.hpp"
#include "ptnet/eval.hpp"

namespace ptnet {

// The report's files that need `force` when they exist (write_report checks
// them before writing any); check_report_outputs checks them, folder or not
// yet, and run_evaluation does so before evaluating a single pair.
inline constexpr const char* kReportFiles[] = {"metrics.csv", "metrics.json", "index.html"};
void check_report_outputs(const std::string& out_dir, bool force);

// The paper's Table 2: {"seen"|"unseen": {category|"average": [RMSE (its sensor's units, not kPa), binary R^2]}}.
nlohmann::json paper_table2();

// A figure of one pair (source / ground truth / transferred / |error|).
struct PairFigure {
  EvalRow row;      // the model's row of the pair
  std::string png;  // file name in the report folder
  std::string gif;  // animation beside it ("" for none)
};

// The `count` model rows with the highest RMSE, worst first.
std::vector<EvalRow> worst_pairs(const std::vector<EvalRow>& rows, int count);

// Writes index.html and its SVG charts (chart_*.svg, training_curve.svg) into
// options.out_dir: Table 2 with every method the rows hold beside the paper's
// figures, bar charts per metric, the per-category and worst-pair figures,
// the model's training curve and config (options.model_dir, when given).
// Returns the paths written.
std::vector<std::string> write_report_html(const std::vector<EvalRow>& rows,
                                           const std::vector<PairFigure>& categories,
                                           const std::vector<PairFigure>& worst,
                                           const std::string& dataset_path,
                                           const ReportOptions& options);

}  // namespace ptnet
