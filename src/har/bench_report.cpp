// The body-shift HAR benchmark's outputs (ptnet/har_bench.hpp): the tables
// as text, results.json, and one offline page (index.html + f1.svg).
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ptnet/error.hpp"
#include "ptnet/har_bench.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/viz.hpp"

namespace ptnet::har {
namespace {

std::string body_text(const BodySpec& b) {
  return b.id + " (" + sex_name(b.sex) + ", " + fixed_text(b.height_cm, 1) + " cm, " + fixed_text(b.weight_kg, 1) +
         " kg)";
}

std::string percent(double fraction) {
  return std::isfinite(fraction) ? std::to_string(int(std::lround(100 * fraction))) + " %" : "-";
}

// "model - copy: +0.018 (2.0 paired sd; higher in 9 of 10 runs; 1.1 run sd)",
// "[xlarge] model - copy: ..." for a band's windows.
std::string comparison_text(const BenchComparison& c, int runs) {
  const auto ratio = [&](double sd) { return sd > 0 ? fixed_text(c.difference / sd, 1) : std::string("-"); };
  return (c.band.empty() ? "" : "[" + c.band + "] ") + c.source + " - " + c.baseline + ": " +
         (c.difference >= 0 ? "+" : "") + fixed_text(c.difference) + " (" + ratio(c.paired_sd) +
         " paired sd; higher in " + std::to_string(c.wins) + " of " + std::to_string(runs) + " runs; " + ratio(c.run_sd) + " run sd)";
}

double mean_over_runs(const std::vector<double>& runs) {
  double m = 0;
  for (double v : runs) m += v / double(runs.size());
  return m;
}

// " (each an ensemble of K classifiers)", or nothing for one classifier a run.
std::string ensemble_text(const BenchResult& r) {
  return r.ensemble > 1 ? " (each an ensemble of " + std::to_string(r.ensemble) + " classifiers)" : "";
}

// A table's per-class F1, per-body macro F1 and confusions (HTML).
void write_detail_tables(std::ostringstream& b, const BenchTable& t, const BenchResult& r) {
  b << "<h3>Per-class F1 (mean over runs)</h3>\n<table><tr><th>class (test windows)</th>";
  for (const BenchSource& s : t.sources) b << "<th>" << html_escape(s.name) << "</th>";
  b << "</tr>\n";
  for (std::size_t c = 0; c < t.classes.size(); ++c) {
    b << "<tr><td>" << html_escape(t.classes[c]) << " (" << t.test_support[c] << ")</td>";
    for (const BenchSource& s : t.sources) b << "<td class=\"num\">" << fixed_text(s.class_f1[c]) << "</td>";
    b << "</tr>\n";
  }
  b << "</table>\n<h3>Macro F1 per deployment body (mean over runs)</h3>\n<table><tr><th>body</th>";
  for (const BenchSource& s : t.sources) b << "<th>" << html_escape(s.name) << "</th>";
  b << "</tr>\n";
  for (std::size_t d = 0; d < r.deployment.size(); ++d) {
    b << "<tr><td>" << html_escape(body_text(r.deployment[d])) << "</td>";
    for (const BenchSource& s : t.sources) b << "<td class=\"num\">" << fixed_text(mean_over_runs(s.body_f1[d])) << "</td>";
    b << "</tr>\n";
  }
  for (std::size_t band = 0; band < t.bands.size(); ++band) {
    b << "<tr><td>band " << html_escape(t.bands[band]) << " (its bodies' windows)</td>";
    for (const BenchSource& s : t.sources)
      b << "<td class=\"num\">" << fixed_text(mean_over_runs(s.band_f1[band])) << "</td>";
    b << "</tr>\n";
  }
  b << "</table>\n<h3>Confusion (summed over runs; rows true, columns predicted)</h3>\n<div class=\"charts\">\n";
  for (const BenchSource& s : t.sources) {
    b << "<table class=\"confusion\"><caption>" << html_escape(s.name) << "</caption>\n<tr><th>true \\ predicted</th>";
    for (const std::string& c : t.classes) b << "<th>" << html_escape(c) << "</th>";
    b << "</tr>\n";
    for (int i = 0; i < s.confusion.rows(); ++i) {
      b << "<tr><th>" << html_escape(t.classes[std::size_t(i)]) << "</th>";
      const double total = std::max(1, s.confusion.row(i).sum());
      for (int k = 0; k < s.confusion.cols(); ++k) {
        const double share = s.confusion(i, k) / total;
        b << "<td class=\"num\" style=\"background: rgba(8, 48, 107, " << fixed_text(share, 2) << ")"
          << (share > 0.5 ? "; color: #fff" : "") << "\">" << s.confusion(i, k) << "</td>";
      }
      b << "</tr>\n";
    }
    b << "</table>\n";
  }
  b << "</div>\n";
}

}  // namespace

std::string format_bench(const BenchResult& r) {
  std::ostringstream o;
  for (const BenchTable& t : r.tables) {
    o << "Macro F1 on the deployment bodies' test windows (" << t.labels << " labels, " << t.classes.size()
      << " classes), mean +- sd over " << r.runs << " runs" << ensemble_text(r) << "\n";
    o << "  source          macro F1        gap closed  training windows\n";
    for (const BenchSource& s : t.sources) {
      char line[160];
      std::snprintf(line, sizeof line, "  %-14s  %.3f +- %.3f   %-10s  %d\n", s.name.c_str(), s.mean, s.sd,
                    percent(s.gap_closed).c_str(), s.train_windows);
      o << line;
    }
    o << "  gap (oracle - recorded): " << fixed_text(t.gap) << "\n";
    for (const BenchComparison& c : t.comparisons) o << "  " << comparison_text(c, r.runs) << "\n";
    o << "\n";
  }
  return o.str();
}

std::string bench_json(const BenchResult& r) {
  nlohmann::json j;
  j["mocap"] = r.mocap;
  j["activities"] = r.activities;
  j["left_out"] = r.left_out;
  j["clips"] = r.clips;
  j["runs"] = r.runs;
  j["ensemble"] = r.ensemble;
  j["windows"] = {{"recorded", r.recorded_windows}, {"per_synthesis", r.synthetic_windows}, {"test", r.test_windows}};
  for (const auto* pop : {&r.recorded, &r.deployment}) {
    nlohmann::json bodies = nlohmann::json::array();
    for (const BodySpec& b : *pop)
      bodies.push_back({{"id", b.id}, {"sex", sex_name(b.sex)}, {"height_cm", b.height_cm}, {"weight_kg", b.weight_kg}});
    j[pop == &r.recorded ? "recorded_bodies" : "deployment_bodies"] = bodies;
  }
  j["tables"] = nlohmann::json::array();
  for (const BenchTable& t : r.tables) {
    nlohmann::json jt = {{"labels", t.labels},   {"classes", t.classes}, {"test_support", t.test_support},
                         {"gap", t.gap},         {"bands", t.bands}};
    jt["sources"] = nlohmann::json::array();
    for (const BenchSource& s : t.sources) {
      nlohmann::json confusion = nlohmann::json::array();
      for (int i = 0; i < s.confusion.rows(); ++i) {
        std::vector<int> row;
        for (int k = 0; k < s.confusion.cols(); ++k) row.push_back(s.confusion(i, k));
        confusion.push_back(row);
      }
      jt["sources"].push_back({{"name", s.name},
                               {"train_windows", s.train_windows},
                               {"macro_f1", s.macro_f1},
                               {"mean", s.mean},
                               {"sd", s.sd},
                               {"gap_closed", std::isfinite(s.gap_closed) ? nlohmann::json(s.gap_closed) : nlohmann::json()},
                               {"class_f1", s.class_f1},
                               {"body_f1", s.body_f1},
                               {"band_f1", s.band_f1},
                               {"confusion", confusion}});
    }
    jt["comparisons"] = nlohmann::json::array();
    for (const BenchComparison& c : t.comparisons)
      jt["comparisons"].push_back({{"source", c.source},
                                   {"baseline", c.baseline},
                                   {"band", c.band.empty() ? nlohmann::json() : nlohmann::json(c.band)},
                                   {"difference", c.difference},
                                   {"paired_sd", c.paired_sd},
                                   {"run_sd", c.run_sd},
                                   {"wins", c.wins}});
    j["tables"].push_back(jt);
  }
  j["seconds"] = {{"simulate", r.simulate_seconds},
                  {"transfer", r.transfer_seconds},
                  {"classify", r.classify_seconds},
                  {"total", r.seconds}};
  return j.dump(2) + "\n";
}

std::vector<std::string> write_bench_report(const std::string& out_dir, const BenchResult& r, bool force) {
  namespace fs = std::filesystem;
  const auto path = [&](const std::string& name) { return (fs::path(out_dir) / name).string(); };
  std::ostringstream b;
  b << "<h1>ptnet HAR body-shift benchmark</h1>\n<p>Clips: <code>" << html_escape(r.mocap) << "</code>, " << r.clips
    << " clips of " << r.activities.size() << " activities (" << html_escape(join(r.activities)) << "). "
    << r.recorded_windows << " recorded training windows, " << r.synthetic_windows
    << " added per training source, " << r.test_windows << " test windows of the deployment bodies; " << r.runs
    << " seeded runs per source" << ensemble_text(r) << ". Every number: <a href=\"results.json\">results.json</a>.</p>\n"
    << "<img src=\"f1.svg\" alt=\"macro F1 per training source with its spread\">\n";
  BarChart chart;
  chart.title = "Macro F1 on the deployment bodies (whiskers: +- 1 sd over runs)";
  chart.y_label = "macro F1";
  chart.width = 640;
  for (const BenchTable& t : r.tables) {
    BarSeries series{t.labels + " labels", {}, {}};
    b << "<h2>Macro F1, " << html_escape(t.labels) << " labels</h2>\n<table id=\"bench_" << html_escape(t.labels)
      << "\"><tr><th>training source</th><th>macro F1 (mean &plusmn; sd)</th><th>gap closed</th><th>training "
         "windows</th><th>per run</th></tr>\n";
    for (const BenchSource& s : t.sources) {
      std::string runs;
      for (double v : s.macro_f1) runs += (runs.empty() ? "" : " ") + fixed_text(v);
      b << "<tr><td>" << html_escape(s.name) << "</td><td class=\"num\" data-source=\"" << html_escape(s.name)
        << "\">" << fixed_text(s.mean) << " &plusmn; " << fixed_text(s.sd) << "</td><td class=\"num\">"
        << percent(s.gap_closed) << "</td><td class=\"num\">" << s.train_windows << "</td><td class=\"num runs\">"
        << runs << "</td></tr>\n";
      if (&t == &r.tables.front()) chart.groups.push_back(s.name);
      series.values.push_back(s.mean);
      series.errors.push_back(s.sd);
    }
    b << "</table>\n";
    chart.series.push_back(series);
    if (!t.comparisons.empty()) {
      b << "<p>Run by run (run r of every source trains from the same seeds):</p>\n<ul>\n";
      for (const BenchComparison& c : t.comparisons)
        b << "<li>" << html_escape(comparison_text(c, r.runs)) << "</li>\n";
      b << "</ul>\n";
    }

    write_detail_tables(b, t, r);
  }
  b << "<h2>Bodies</h2>\n<p>Recorded: ";
  for (const BodySpec& x : r.recorded) b << html_escape(body_text(x)) << "; ";
  b << "</p>\n<p>Deployment: ";
  for (const BodySpec& x : r.deployment) b << html_escape(body_text(x)) << "; ";
  b << "</p>\n";
  if (!r.left_out.empty()) {
    b << "<h2>Left out</h2>\n<ul>\n";
    for (const std::string& l : r.left_out) b << "<li>" << html_escape(l) << "</li>\n";
    b << "</ul>\n";
  }
  b << "<p class=\"note\">Time: simulation " << fixed_text(r.simulate_seconds, 1) << " s, synthesis "
    << fixed_text(r.transfer_seconds, 1) << " s, classifiers " << fixed_text(r.classify_seconds, 1) << " s, total "
    << fixed_text(r.seconds, 1) << " s.</p>\n";
  std::vector<std::string> written;
  write_text_file(path("f1.svg"), svg_bar_chart(chart), force);
  written.push_back(path("f1.svg"));
  write_text_file(path("index.html"), html_page("ptnet HAR body-shift benchmark", b.str()), force);
  written.push_back(path("index.html"));
  return written;
}

}  // namespace ptnet::har
