// report/index.html: the evaluation report as one offline page (html_report.hpp).
//
// Data-driven: every method the rows hold (model, baselines, a noise floor)
// gets its columns and bars, in summarise()'s order. Table cells carry
// data-method / data-group / data-split / data-metric so the browser test can
// compare them with metrics.csv.
#include "html_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <tuple>

#include "core/csv.hpp"
#include "eval_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/viz.hpp"

namespace ptnet {
namespace fs = std::filesystem;
namespace {

const char* split_name(bool seen) { return seen ? "seen" : "unseen"; }

// What each known method is; others are shown by their name.
std::string method_label(const std::string& m) {
  if (m == "model") return "model";
  if (m == "model_raw") return "model (raw)";
  if (m == "copy") return "copy";
  if (m == "weight_ratio") return "weight ratio";
  if (m == "body_scale") return "body scale";
  if (m == "floor") return "noise floor";
  return m;
}
std::string method_note(const std::string& m) {
  if (m == "model") return "the trained network (this report's model folder), its fitted contact threshold applied";
  if (m == "model_raw") return "the same network's raw output, without the contact threshold";
  if (m == "copy") return "baseline: the source sequence unchanged";
  if (m == "weight_ratio") return "baseline: the source scaled by the target/source weight ratio";
  if (m == "body_scale")
    return "baseline (ours): the source zoomed by the height ratio about the mat centre and scaled "
           "by "
           "weight over area ratio";
  if (m == "floor") return "reference: the noise floor, what no method can beat (docs/results.md)";
  return "method '" + m + "' from metrics.csv";
}

using Key = std::tuple<std::string, std::string, bool>;  // method, group, seen

struct Summary {
  std::vector<std::string> methods;                 // in table order
  std::map<bool, std::vector<std::string>> groups;  // per split: categories, then "average"
  std::map<Key, GroupSummary> at;
  const GroupSummary* find(const std::string& m, const std::string& g, bool seen) const {
    auto it = at.find({m, g, seen});
    return it == at.end() ? nullptr : &it->second;
  }
};

Summary summary_of(const std::vector<EvalRow>& rows) {
  Summary s;
  for (const auto& g : summarise(rows)) {
    if (std::find(s.methods.begin(), s.methods.end(), g.method) == s.methods.end())
      s.methods.push_back(g.method);
    auto& groups = s.groups[g.seen];
    if (std::find(groups.begin(), groups.end(), g.group) == groups.end()) groups.push_back(g.group);
    s.at[{g.method, g.group, g.seen}] = g;
  }
  for (auto& [seen, groups] : s.groups)  // "average" last
    std::stable_partition(groups.begin(), groups.end(),
                          [](const std::string& g) { return g != "average"; });
  return s;
}

std::string cell(const std::string& method, const std::string& group, bool seen,
                 const std::string& metric, const std::string& text,
                 const std::string& cls = "num") {
  return "<td class=\"" + cls + "\" data-method=\"" + html_escape(method) + "\" data-group=\"" +
         html_escape(group) + "\" data-split=\"" + split_name(seen) + "\" data-metric=\"" + metric +
         "\">" + text + "</td>";
}

const nlohmann::json* paper_value(const nlohmann::json& paper, bool seen,
                                  const std::string& group) {
  const auto& split = paper.at(split_name(seen));
  return split.contains(group) ? &split.at(group) : nullptr;
}

std::string table2_html(const Summary& s) {
  const nlohmann::json paper = paper_table2();
  const bool has_model = std::find(s.methods.begin(), s.methods.end(), "model") != s.methods.end();
  std::ostringstream o;
  o << "<table id=\"table2\">\n<tr><th rowspan=\"2\">Motion category</th><th "
       "rowspan=\"2\">pairs</th>";
  for (const auto& m : s.methods)
    o << "<th colspan=\"2\">" << html_escape(method_label(m)) << "</th>";
  o << "<th colspan=\"2\">paper (Table 2)</th>";
  if (has_model) o << "<th colspan=\"3\">model, more metrics</th>";
  o << "</tr>\n<tr>";
  for (std::size_t i = 0; i < s.methods.size(); ++i) o << "<th>RMSE (kPa)</th><th>bin. R&sup2;</th>";
  o << "<th>RMSE (its units)</th><th>bin. R&sup2;</th>";
  if (has_model) o << "<th>CoP err. (cm)</th><th>force err. (%)</th><th>contact IoU</th>";
  o << "</tr>\n";
  const int columns = 2 + 2 * int(s.methods.size() + 1) + (has_model ? 3 : 0);
  for (bool seen : {true, false}) {
    auto it = s.groups.find(seen);
    if (it == s.groups.end()) continue;
    o << "<tr class=\"section\"><th colspan=\"" << columns << "\">"
      << (seen ? "Seen motions (take 1)" : "Unseen motions (take 2)") << "</th></tr>\n";
    for (const auto& group : it->second) {
      const GroupSummary* first = s.find(s.methods.front(), group, seen);
      o << "<tr" << (group == "average" ? " class=\"average\"" : "") << "><td>"
        << (group == "average" ? "Average" : html_escape(group)) << "</td>"
        << cell(s.methods.front(), group, seen, "rows", std::to_string(first ? first->rows : 0));
      for (const auto& m : s.methods) {
        const GroupSummary* g = s.find(m, group, seen);
        o << cell(m, group, seen, "rmse_kpa", g ? fixed_text(g->mean.rmse_kpa, 2) : "&ndash;")
          << cell(m, group, seen, "binary_r2", g ? fixed_text(g->mean.binary_r2, 3) : "&ndash;");
      }
      const nlohmann::json* p = paper_value(paper, seen, group);
      o << cell("paper", group, seen, "rmse_kpa", p ? fixed_text((*p)[0].get<double>(), 2) : "&ndash;",
                "num paper")
        << cell("paper", group, seen, "binary_r2", p ? fixed_text((*p)[1].get<double>(), 2) : "&ndash;",
                "num paper");
      if (has_model) {
        const GroupSummary* g = s.find("model", group, seen);
        o << cell("model", group, seen, "cop_error_cm",
                  g ? fixed_text(g->mean.cop_error_cm, 2) : "&ndash;")
          << cell("model", group, seen, "force_error_pct",
                  g ? fixed_text(g->mean.force_error_pct, 1) : "&ndash;")
          << cell("model", group, seen, "contact_iou",
                  g ? fixed_text(g->mean.contact_iou, 3) : "&ndash;");
      }
      o << "</tr>\n";
    }
  }
  o << "</table>\n<ul class=\"note\">\n";
  for (const auto& m : s.methods)
    o << "<li><b>" << html_escape(method_label(m)) << "</b>: " << html_escape(method_note(m))
      << "</li>\n";
  o << "<li><b>paper</b>: the model's figures in the paper's Table 2 (its simulator's data, ours are "
       "another simulator's; its RMSE is in its sensor's units, which it does not state: not kPa, so not "
       "on the RMSE charts)</li>\n"
    << "</ul>\n";
  return o.str();
}

// One SVG per metric and split: groups = categories and the average, bars =
// methods; the paper's bars on the binary R^2 charts only (its RMSE is not in
// kPa: no number of another unit on a kPa axis).
std::vector<std::pair<std::string, std::string>> bar_charts(const Summary& s) {
  const nlohmann::json paper = paper_table2();
  std::vector<std::pair<std::string, std::string>> charts;  // file name, SVG
  for (bool seen : {true, false}) {
    auto it = s.groups.find(seen);
    if (it == s.groups.end()) continue;
    for (const auto& [metric, label] :
         {std::pair<std::string, std::string>{"rmse_kpa", "RMSE (kPa), lower is better"},
          {"binary_r2", "binary R\xc2\xb2, higher is better"}}) {
      BarChart c;
      c.title = std::string(metric == "rmse_kpa" ? "RMSE" : "Binary R\xc2\xb2") + ", " +
                split_name(seen) + " motions";
      c.y_label = label;
      c.groups = it->second;
      c.width = 600;
      for (const auto& m : s.methods) {
        BarSeries b{method_label(m), {}, {}};
        for (const auto& g : c.groups) {
          const GroupSummary* x = s.find(m, g, seen);
          b.values.push_back(!x                     ? NAN
                             : metric == "rmse_kpa" ? x->mean.rmse_kpa
                                                    : x->mean.binary_r2);
        }
        c.series.push_back(b);
      }
      if (metric == "binary_r2") {
        BarSeries p{"paper", {}, {}};
        for (const auto& g : c.groups) {
          const nlohmann::json* v = paper_value(paper, seen, g);
          p.values.push_back(v ? (*v)[1].get<double>() : NAN);
        }
        c.series.push_back(p);
      }
      charts.emplace_back("chart_" + metric + "_" + split_name(seen) + ".svg", svg_bar_chart(c));
    }
  }
  return charts;
}

std::string pair_caption(const EvalRow& r) {
  return r.category + " (" + split_name(r.take == 1) + "), motion " + r.motion_id + ": " +
         r.source_body + " \xe2\x86\x92 " + r.target_body + ", " + std::to_string(r.frames) +
         " frames; model RMSE " + fixed_text(r.metrics.rmse_kpa, 2) + " kPa, binary R\xc2\xb2 " +
         fixed_text(r.metrics.binary_r2, 3);
}

std::string figure_html(const PairFigure& f) {
  std::ostringstream o;
  o << "<figure><figcaption>" << html_escape(pair_caption(f.row))
    << ". Rows: source, ground truth, transferred, |error| (one kPa scale).</figcaption>\n<div "
       "class=\"pair\">"
    << "<a href=\"" << html_escape(f.png) << "\"><img class=\"still\" src=\"" << html_escape(f.png)
    << "\" alt=\"" << html_escape("frames of " + f.row.motion_id) << "\"></a>";
  if (!f.gif.empty())
    o << "<img class=\"anim\" src=\"" << html_escape(f.gif) << "\" alt=\""
      << html_escape("animation of " + f.row.motion_id) << "\">";
  o << "</div></figure>\n";
  return o.str();
}

std::string worst_html(const std::vector<EvalRow>& rows, const std::vector<PairFigure>& worst) {
  std::ostringstream o;
  o << "<table "
       "id=\"worst\">\n<tr><th>#</th><th>category</th><th>split</th><th>motion</th><th>source "
       "&rarr; target</th><th>frames</th><th>RMSE model (kPa)</th><th>bin. R&sup2; "
       "model</th><th>RMSE copy "
       "(kPa)</th></tr>\n";
  int rank = 0;
  for (const auto& f : worst) {
    const EvalRow& r = f.row;
    double copy = NAN;
    for (const auto& x : rows)
      if (x.method == "copy" && x.source_sequence == r.source_sequence &&
          x.target_sequence == r.target_sequence)
        copy = x.metrics.rmse_kpa;
    o << "<tr><td>" << ++rank << "</td><td>" << html_escape(r.category) << "</td><td>"
      << split_name(r.take == 1) << "</td><td>" << html_escape(r.motion_id) << "</td><td>"
      << html_escape(r.source_body) << " &rarr; " << html_escape(r.target_body)
      << "</td><td class=\"num\">" << r.frames << "</td><td class=\"num\">"
      << fixed_text(r.metrics.rmse_kpa, 2) << "</td><td class=\"num\">" << fixed_text(r.metrics.binary_r2, 3)
      << "</td><td class=\"num\">" << (std::isnan(copy) ? "&ndash;" : fixed_text(copy, 2))
      << "</td></tr>\n";
  }
  o << "</table>\n";
  for (const auto& f : worst) o << figure_html(f);
  return o.str();
}

// history.csv columns by name (core's CSV reader): epoch, train_loss,
// val_loss (others ignored).
LineChart training_chart(const std::string& history_path) {
  const CsvTable t = read_csv(history_path);
  const std::string columns = "epoch,train_loss,val_loss";
  const int ce = t.required("epoch", columns), ct = t.required("train_loss", columns),
            cv = t.required("val_loss", columns);
  LineChart c;
  c.title = "Training curve";
  c.x_label = "epoch";
  c.y_label = "loss (normalised MSE)";
  c.series = {{"train", {}, {}}, {"validation", {}, {}}};
  for (const CsvRow& row : t.rows) {
    double epoch = 0, train = 0, val = 0;
    if (!parse_number(CsvTable::field(row, ce), epoch) || !parse_number(CsvTable::field(row, ct), train) ||
        !parse_number(CsvTable::field(row, cv), val))
      throw Error::at(history_path, row.line, "numbers in columns " + columns, escaped(join(row.fields), 60));
    c.series[0].x.push_back(epoch);
    c.series[0].y.push_back(train);
    c.series[1].x.push_back(epoch);
    c.series[1].y.push_back(val);
  }
  return c;
}

}  // namespace

std::vector<EvalRow> worst_pairs(const std::vector<EvalRow>& rows, int count) {
  std::vector<EvalRow> model;
  for (const auto& r : rows)
    if (r.method == "model") model.push_back(r);
  std::stable_sort(model.begin(), model.end(), [](const EvalRow& a, const EvalRow& b) {
    return a.metrics.rmse_kpa > b.metrics.rmse_kpa;
  });
  if (int(model.size()) > count) model.resize(std::size_t(std::max(0, count)));
  return model;
}

std::vector<std::string> write_report_html(const std::vector<EvalRow>& rows,
                                           const std::vector<PairFigure>& categories,
                                           const std::vector<PairFigure>& worst,
                                           const std::string& dataset_path,
                                           const ReportOptions& options) {
  const auto path = [&](const std::string& name) {
    return (fs::path(options.out_dir) / name).string();
  };
  std::vector<std::string> written;
  const Summary s = summary_of(rows);
  int pairs = 0;
  for (const auto& r : rows) pairs += r.method == "model";

  std::ostringstream b;
  b << "<h1>ptnet evaluation report</h1>\n<p>Dataset <code>" << html_escape(dataset_path)
    << "</code>";
  if (!options.model_dir.empty())
    b << ", model <code>" << html_escape(options.model_dir) << "</code>";
  b << "; " << pairs
    << " test pairs (ordered pairs of two original bodies on the same motion); binary R&sup2; and "
    << "IoU threshold " << fixed_text(options.threshold_kpa, 2)
    << " kPa. Every number: <a href=\"metrics.csv\">metrics.csv</a>"
    << " (one row per pair and method), <a href=\"metrics.json\">metrics.json</a> (group "
       "means).</p>\n";
  if (!options.warning.empty())
    b << "<p class=\"warning\"><b>Warning:</b> the model's " << html_escape(options.warning) << ".</p>\n";
  b << "<h2>Table 2: per category, seen and unseen motions</h2>\n";
  if (s.methods.empty())
    b << "<p>No evaluated pairs.</p>\n";
  else
    b << table2_html(s);

  b << "<h2>Charts</h2>\n<div class=\"charts\">\n";
  for (const auto& [name, svg] : bar_charts(s)) {
    write_text_file(path(name), svg, options.force);
    written.push_back(path(name));
    b << "<img src=\"" << html_escape(name) << "\" alt=\"" << html_escape(name) << "\">\n";
  }
  b << "</div>\n";

  b << "<h2>One pair per category</h2>\n<p class=\"note\">The first seen pair of each category "
       "(test_pairs order); "
       "the still shows evenly spaced frames at full size, the animation the whole pair in real "
       "time "
       "(at most 150 frames).</p>\n";
  for (const auto& f : categories)
    b << "<h3>" << html_escape(f.row.category) << "</h3>\n" << figure_html(f);

  b << "<h2>The " << worst.size()
    << " worst pairs (model RMSE)</h2>\n<p class=\"note\">Each figure shows the pair's "
       "frames with the largest summed |error|.</p>\n"
    << worst_html(rows, worst);

  b << "<h2>Model</h2>\n";
  if (options.model_dir.empty()) {
    b << "<p>No model folder given.</p>\n";
  } else {
    const ModelFiles files(options.model_dir);
    const fs::path history = files.history();
    if (fs::exists(history)) {
      write_text_file(path("training_curve.svg"), svg_line_chart(training_chart(history.string())),
                      options.force);
      written.push_back(path("training_curve.svg"));
      b << "<img src=\"training_curve.svg\" alt=\"training curve: train and validation loss per "
           "epoch\">\n";
    } else {
      b << "<p>No training history (" << html_escape(history.string()) << " is missing).</p>\n";
    }
    const fs::path config = files.config();
    if (fs::exists(config))
      b << "<details open><summary>" << ModelFiles::kConfig << " (architecture, normalisation, training data and "
           "options, final "
           "metrics)</summary><pre>"
        << html_escape(read_text_file(config.string())) << "</pre></details>\n";
  }
  write_text_file(path("index.html"), html_page("ptnet evaluation report", b.str()), options.force);
  written.push_back(path("index.html"));
  return written;
}

}  // namespace ptnet
