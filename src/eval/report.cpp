// The evaluation report: metrics files and qualitative figures (eval.hpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>

#include "eval_internal.hpp"
#include "html_report.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/io.hpp"
#include "ptnet/viz.hpp"

namespace ptnet {
namespace fs = std::filesystem;

nlohmann::json paper_table2() {
  nlohmann::json seen, unseen;
  for (const PaperTable2Row& r : kPaperTable2) {
    seen[r.category] = {r.seen_rmse, r.seen_binary_r2};
    unseen[r.category] = {r.unseen_rmse, r.unseen_binary_r2};
  }
  return {{"seen", seen}, {"unseen", unseen}};
}

std::string paper_table2_line() {
  const PaperTable2Row& a = kPaperTable2[std::size(kPaperTable2) - 1];
  return "Paper (Table 2): seen RMSE " + fixed_text(a.seen_rmse, 2) + ", binary R^2 " +
         fixed_text(a.seen_binary_r2, 2) + "; unseen RMSE " + fixed_text(a.unseen_rmse, 2) + ", binary R^2 " +
         fixed_text(a.unseen_binary_r2, 2) + " (its RMSE in its sensor's units, not kPa)";
}

namespace {

nlohmann::json metrics_json(const SequenceMetrics& m) {
  return {{"rmse_kpa", m.rmse_kpa},         {"binary_r2", m.binary_r2},
          {"cop_error_cm", m.cop_error_cm}, {"force_error_pct", m.force_error_pct},
          {"contact_iou", m.contact_iou}};
}

constexpr int kStillCellPx = 4;  // px per mat cell in the stills: a category's figure ~1070 x 1640 px
constexpr int kWorstPairs = 5;   // worst pairs (model RMSE) with figures on the page

std::string body_label(const BodySpec& b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s, %.0f cm, %.0f kg", sex_name(b.sex), b.height_cm, b.weight_kg);
  return buf;
}

PressureSequence absolute_error(const PressureSequence& a, const PressureSequence& b) {
  PressureSequence e = a;
  for (std::size_t i = 0; i < e.kpa.size(); ++i) e.kpa[i] = std::abs(a.kpa[i] - b.kpa[i]);
  return e;
}

// The `count` frames with the largest summed |error|, at least T / (2 count)
// frames apart, in time order.
std::vector<int> worst_frames(const PressureSequence& err, int count) {
  const int t_count = err.frames(), cells = err.mat.cells();
  std::vector<std::pair<double, int>> by_error;
  for (int t = 0; t < t_count; ++t) {
    double sum = 0;
    for (int i = 0; i < cells; ++i) sum += err.kpa[std::size_t(t) * cells + i];
    by_error.emplace_back(-sum, t);
  }
  std::sort(by_error.begin(), by_error.end());
  const int gap = std::max(1, t_count / (2 * std::max(1, count)));
  std::vector<int> picked;
  for (const auto& [neg, t] : by_error) {
    if (int(picked.size()) == count) break;
    if (std::all_of(picked.begin(), picked.end(), [&](int p) { return std::abs(p - t) >= gap; })) picked.push_back(t);
  }
  std::sort(picked.begin(), picked.end());
  return picked;
}

// Source / ground truth / transferred / |error| of one pair, transferred
// again with `model`; `still` and `gif` (when not empty) name the files. The
// still shows `frames` evenly spaced frames, or the worst ones (worst_frames).
void write_pair_figure(const Dataset& dataset, const TestPair& pair, const TransferFn& model,
                       const std::string& still, const std::string& gif, int frames, bool worst, bool force) {
  const PairData data = load_pair(dataset, pair);
  const PressureSequence out = model(data.source, data.source_body, data.target_body);
  const PressureSequence err = absolute_error(out, data.truth);
  const std::string tag = pair.category + (pair.take == 1 ? " (seen) " : " (unseen) ");
  const std::vector<FigurePanel> panels{{tag + "source", body_label(data.source_body), &data.source},
                                        {tag + "ground truth", body_label(data.target_body), &data.truth},
                                        {tag + "transferred", body_label(data.target_body), &out},
                                        {tag + "|error|", "same kPa scale", &err}};
  FigureOptions fo;
  fo.frames = frames;
  if (worst) fo.frame_list = worst_frames(err, frames);
  fo.cell_px = kStillCellPx;
  write_png(still, render_strip(panels, fo), force);
  if (gif.empty()) return;
  FigureOptions go;
  go.frames = std::min(data.truth.frames(), 150);  // about 5 s at 30 Hz keeps the GIF small
  std::vector<int> delays;
  const auto animation = render_animation(panels, go, &delays);
  write_gif(gif, animation, delays, force);
}

TestPair pair_of(const EvalRow& r) {
  return TestPair{r.motion_id, r.category, r.take, r.source_sequence, r.target_sequence};
}

}  // namespace

void check_report_outputs(const std::string& out_dir, bool force) {
  check_outputs_in_folder(out_dir, std::vector<std::string>(std::begin(kReportFiles), std::end(kReportFiles)), force);
}

std::vector<std::string> write_report(const Dataset& dataset, const std::vector<EvalRow>& rows,
                                      const TransferFn& model, const ReportOptions& options) {
  make_folder(options.out_dir);
  const auto path = [&](const std::string& name) { return (fs::path(options.out_dir) / name).string(); };
  // Refuse before writing anything, so a refused run leaves no partial report.
  for (const char* name : kReportFiles) check_output_path(path(name), options.force);

  std::vector<std::string> written;
  CommitGroup report;  // every file appears at the end, or none (a failure keeps the previous report)
  write_text_file(path("metrics.csv"), format_metrics_csv(rows), options.force);
  written.push_back(path("metrics.csv"));

  nlohmann::json j;
  j["dataset"] = dataset.path();
  j["threshold_kpa"] = options.threshold_kpa;
  j["pairs"] = std::count_if(rows.begin(), rows.end(), [](const EvalRow& r) { return r.method == "model"; });
  const bool floor = std::any_of(rows.begin(), rows.end(), [](const EvalRow& r) { return r.method == "floor"; });
  j["noise_floor"] = floor ? "groups.*.*.floor: the truth simulated again with another sensor seed" : kNoFloorNote;
  j["definitions"] = "see include/ptnet/eval.hpp and docs/results.md";
  j["paper_table2"] = paper_table2();
  if (!options.warning.empty()) j["warning"] = options.warning;
  for (const auto& g : summarise(rows)) {
    nlohmann::json m = metrics_json(g.mean);
    m["rows"] = g.rows;
    j["groups"][g.seen ? "seen" : "unseen"][g.group][g.method] = m;
  }
  write_text_file(path("metrics.json"), j.dump(2) + "\n", options.force);
  written.push_back(path("metrics.json"));

  // Qualitative figures: one seen pair per category (else an unseen one).
  std::map<std::string, TestPair> chosen;
  for (const auto& p : test_pairs(dataset)) {
    auto it = chosen.find(p.category);
    if (it == chosen.end() || (it->second.take != 1 && p.take == 1)) chosen[p.category] = p;
  }
  const auto model_row = [&](const TestPair& p) {
    for (const auto& r : rows)
      if (r.method == "model" && r.source_sequence == p.source_sequence && r.target_sequence == p.target_sequence)
        return r;
    EvalRow r;  // a pair the rows do not hold: caption without metrics
    r.method = "model", r.motion_id = p.motion_id, r.category = p.category, r.take = p.take;
    r.source_sequence = p.source_sequence, r.target_sequence = p.target_sequence;
    return r;
  };
  std::vector<PairFigure> categories;
  for (const char* category : {"walking", "rom", "freestyle", "acting"}) {
    auto it = chosen.find(category);
    if (it == chosen.end()) continue;
    const std::string png = std::string("qualitative_") + category + ".png";
    const std::string gif = std::string("qualitative_") + category + ".gif";
    write_pair_figure(dataset, it->second, model, path(png), path(gif), options.frames_per_category,
                      /*worst=*/false, options.force);
    written.push_back(path(png));
    written.push_back(path(gif));
    categories.push_back({model_row(it->second), png, gif});
  }
  std::vector<PairFigure> worst;
  for (const EvalRow& r : worst_pairs(rows, kWorstPairs)) {
    const std::string png = "worst_" + std::to_string(worst.size() + 1) + ".png";
    write_pair_figure(dataset, pair_of(r), model, path(png), "", options.frames_per_category, /*worst=*/true,
                      options.force);
    written.push_back(path(png));
    worst.push_back({r, png, ""});
  }
  for (const auto& p : write_report_html(rows, categories, worst, dataset.path(), options)) written.push_back(p);
  report.commit();
  return written;
}

}  // namespace ptnet
