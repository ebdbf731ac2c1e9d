// The evaluation report: metrics files and qualitative figures (eval.hpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/io.hpp"
#include "ptnet/viz.hpp"

namespace ptnet {
namespace fs = std::filesystem;
namespace {

// The paper's Table 2 (RMSE, binary R^2), for metrics.json.
nlohmann::json paper_table() {
  return {{"seen",
           {{"walking", {8.72, 0.81}}, {"rom", {9.21, 0.78}}, {"freestyle", {8.93, 0.80}},
            {"acting", {9.67, 0.76}}, {"average", {8.88, 0.79}}}},
          {"unseen",
           {{"walking", {12.46, 0.71}}, {"rom", {12.89, 0.69}}, {"freestyle", {13.22, 0.70}},
            {"acting", {12.73, 0.69}}, {"average", {12.82, 0.70}}}}};
}

nlohmann::json metrics_json(const SequenceMetrics& m) {
  return {{"rmse_kpa", m.rmse_kpa},         {"binary_r2", m.binary_r2},
          {"cop_error_cm", m.cop_error_cm}, {"force_error_pct", m.force_error_pct},
          {"contact_iou", m.contact_iou}};
}

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

// Stacks images vertically on the page colour.
Image stack(const std::vector<Image>& parts) {
  int w = 0, h = 0;
  for (const auto& p : parts) {
    w = std::max(w, p.width);
    h += p.height;
  }
  Image out(w, h);
  int y = 0;
  for (const auto& p : parts) {
    out.blit(p, 0, y);
    y += p.height;
  }
  return out;
}

}  // namespace

std::vector<std::string> write_report(const Dataset& dataset, const std::vector<EvalRow>& rows,
                                      const TransferFn& model, const ReportOptions& options) {
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (!fs::is_directory(options.out_dir))
    throw Error::in(options.out_dir, "cannot create the report folder");
  const auto path = [&](const std::string& name) { return (fs::path(options.out_dir) / name).string(); };
  // Refuse before writing anything, so a refused run leaves no partial report.
  std::vector<std::string> names{"metrics.csv", "metrics.json", "qualitative.png"};
  for (const auto& name : names) check_output_path(path(name), options.force);

  std::vector<std::string> written;
  CommitGroup report;  // every file appears at the end, or none (a failure keeps the previous report)
  write_text_file(path("metrics.csv"), format_metrics_csv(rows), options.force);
  written.push_back(path("metrics.csv"));

  nlohmann::json j;
  j["dataset"] = dataset.path();
  j["threshold_kpa"] = options.threshold_kpa;
  j["pairs"] = rows.size() / 3;
  j["definitions"] = "see include/ptnet/eval.hpp and docs/results.md";
  j["paper_table2"] = paper_table();
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
  std::vector<Image> strips;
  for (const char* category : {"walking", "rom", "freestyle", "acting"}) {
    auto it = chosen.find(category);
    if (it == chosen.end()) continue;
    const TestPair& p = it->second;
    const PairData data = load_pair(dataset, p);
    const PressureSequence& source = data.source;
    const PressureSequence& truth = data.truth;
    const BodySpec& sb = data.source_body;
    const BodySpec& tb = data.target_body;
    const int frames = truth.frames();
    const PressureSequence out = model(source, sb, tb);
    const PressureSequence err = absolute_error(out, truth);
    const std::string tag = std::string(category) + (p.take == 1 ? " (seen) " : " (unseen) ");
    std::vector<FigurePanel> panels{
        {tag + "source", body_label(sb), &source},
        {tag + "ground truth", body_label(tb), &truth},
        {tag + "transferred", body_label(tb), &out},
        {tag + "|error|", "same kPa scale", &err}};
    FigureOptions fo;
    fo.frames = options.frames_per_category;
    strips.push_back(render_strip(panels, fo));

    FigureOptions go;
    go.frames = std::min(frames, 150);  // about 5 s at 30 Hz keeps the GIF small
    std::vector<int> delays;
    const auto animation = render_animation(panels, go, &delays);
    const std::string gif = path(std::string("qualitative_") + category + ".gif");
    write_gif(gif, animation, delays, options.force);
    written.push_back(gif);
  }
  if (!strips.empty()) {
    write_png(path("qualitative.png"), stack(strips), options.force);
    written.push_back(path("qualitative.png"));
  }
  report.commit();
  return written;
}

}  // namespace ptnet
