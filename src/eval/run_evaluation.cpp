// The whole evaluate step: model, test pairs, table, report (eval.hpp).
#include <filesystem>

#include "eval_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/transfer.hpp"
#include "html_report.hpp"

namespace ptnet {

EvaluationResult run_evaluation(const EvaluationRun& run) {
  check_range("threshold_kpa", run.threshold_kpa, kThresholdKpaRange);
  check_report_outputs(run.out_dir, run.force);  // before the pairs, not after them
  const Dataset dataset = Dataset::open(run.data_path);
  TransferOptions to;
  to.stride = run.stride;
  to.threads = run.threads;
  to.raw = true;  // the fitted threshold is applied below: raw and thresholded from one transfer
  const Transfer net(run.model_dir, to);
  const double threshold = run.raw ? 0.0 : net.model().norm.contact_threshold_kpa;
  const TransferFn raw_model = [&](const PressureSequence& s, const BodySpec& a, const BodySpec& b) {
    return net.run(s, a, b);
  };
  const TransferFn model = [&](const PressureSequence& s, const BodySpec& a, const BodySpec& b) {
    PressureSequence out = net.run(s, a, b);
    zero_below(out, threshold);
    return out;
  };
  EvaluateOptions eo;
  eo.metrics.threshold_kpa = run.threshold_kpa;
  eo.progress = run.progress;
  eo.model_threshold_kpa = threshold;
  EvaluationResult result;
  result.rows = evaluate_pairs(dataset, raw_model, eo);
  ReportOptions ro;
  ro.out_dir = run.out_dir;
  ro.force = run.force;
  ro.threshold_kpa = run.threshold_kpa;
  ro.model_dir = run.model_dir;
  ro.warning = result.warning = baseline_warning(net.model().metrics);
  result.written = write_report(dataset, result.rows, model, ro);
  result.page = (std::filesystem::path(run.out_dir) / "index.html").string();
  result.table = format_table(result.rows);
  return result;
}

}  // namespace ptnet
