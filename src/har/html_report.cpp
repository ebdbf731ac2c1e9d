// har/index.html: the HAR validation as one offline page (ptnet/har.hpp).
//
// Table 3 cells carry data-source / data-metric so the browser test can
// compare them with results.json.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/viz.hpp"

namespace ptnet::har {
namespace {

std::string spread_cell(const std::string& source, const std::string& metric, double mean,
                        double sd) {
  return "<td class=\"num\" data-source=\"" + html_escape(source) + "\" data-metric=\"" + metric +
         "\">" + fixed_text(mean) + " &plusmn; " + fixed_text(sd) + "</td>";
}

std::string table3_html(const HarResult& r) {
  const bool categories = !r.sources.empty() && !r.sources[0].category_macro_f1.empty();
  std::ostringstream o;
  o << "<table id=\"table3\">\n<tr><th>Training dataset source</th>";
  for (const auto& s : r.sources) o << "<th>" << html_escape(source_title(s.source)) << "</th>";
  o << "</tr>\n<tr><td>Macro F1 (pseudo labels), mean &plusmn; std over " << r.runs << " runs</td>";
  for (const auto& s : r.sources)
    o << spread_cell(s.source, "macro_f1", s.macro_f1_mean, s.macro_f1_std);
  if (categories) {
    o << "</tr>\n<tr><td>Macro F1 (categories), mean &plusmn; std</td>";
    for (const auto& s : r.sources)
      o << spread_cell(s.source, "category_macro_f1", s.category_macro_f1_mean,
                       s.category_macro_f1_std);
  }
  o << "</tr>\n<tr><td>Accuracy (pseudo labels), mean</td>";
  for (const auto& s : r.sources)
    o << "<td class=\"num\" data-source=\"" << html_escape(s.source)
      << "\" data-metric=\"accuracy\">" << fixed_text(s.accuracy_mean) << "</td>";
  o << "</tr>\n<tr><td>Macro F1 per run (pseudo labels)</td>";
  for (const auto& s : r.sources) {
    std::string runs;
    for (double v : s.macro_f1) runs += (runs.empty() ? "" : " ") + fixed_text(v);
    o << "<td class=\"num runs\">" << runs << "</td>";
  }
  o << "</tr>\n<tr><td>Training windows</td>";
  for (const auto& s : r.sources) o << "<td class=\"num\">" << s.train_windows << "</td>";
  o << "</tr>\n</table>\n";
  return o.str();
}

std::string f1_chart(const HarResult& r) {
  const bool categories = !r.sources.empty() && !r.sources[0].category_macro_f1.empty();
  BarChart c;
  c.title = "Macro F1 on the test subjects (whiskers: +- 1 std over runs)";
  c.y_label = "macro F1";
  c.width = 560;
  BarSeries pseudo{"pseudo labels", {}, {}}, cats{"categories", {}, {}};
  for (const auto& s : r.sources) {
    c.groups.push_back(source_title(s.source));
    pseudo.values.push_back(s.macro_f1_mean);
    pseudo.errors.push_back(s.macro_f1_std);
    cats.values.push_back(s.category_macro_f1_mean);
    cats.errors.push_back(s.category_macro_f1_std);
  }
  c.series.push_back(pseudo);
  if (categories) c.series.push_back(cats);
  return svg_bar_chart(c);
}

// Rows = true label, columns = predicted; shading = share of the row.
std::string confusion_html(const std::string& title, const Eigen::MatrixXi& m,
                           const std::vector<std::string>& names) {
  std::ostringstream o;
  o << "<table class=\"confusion\"><caption>" << html_escape(title)
    << "</caption>\n<tr><th>true \\ predicted</th>";
  for (int j = 0; j < m.cols(); ++j)
    o << "<th>" << html_escape(j < int(names.size()) ? names[std::size_t(j)] : std::to_string(j))
      << "</th>";
  o << "</tr>\n";
  for (int i = 0; i < m.rows(); ++i) {
    o << "<tr><th>"
      << html_escape(i < int(names.size()) ? names[std::size_t(i)] : std::to_string(i)) << "</th>";
    const double total = std::max(1, m.row(i).sum());
    for (int j = 0; j < m.cols(); ++j) {
      const double share = m(i, j) / total;
      o << "<td class=\"num\" style=\"background: rgba(8, 48, 107, " << fixed_text(share, 2) << ")"
        << (share > 0.5 ? "; color: #fff" : "") << "\" title=\"" << fixed_text(100 * share, 1)
        << " % of row\">" << m(i, j) << "</td>";
    }
    o << "</tr>\n";
  }
  o << "</table>\n";
  return o.str();
}

}  // namespace

std::vector<std::string> write_html_report(const std::string& out_dir, const HarResult& r,
                                           bool force) {
  namespace fs = std::filesystem;
  const auto path = [&](const std::string& name) { return (fs::path(out_dir) / name).string(); };
  std::vector<std::string> written;
  std::ostringstream b;
  b << "<h1>ptnet HAR validation</h1>\n<p>Real recordings <code>" << html_escape(r.dataset)
    << "</code>: train subjects " << html_escape(join(r.train_subjects, ", ")) << " (" << r.train_windows
    << " windows), test subjects " << html_escape(join(r.test_subjects, ", ")) << " (" << r.test_windows
    << " windows), stride " << r.stride << ", " << r.runs
    << " seeded runs per source. Pseudo labels: " << html_escape(pseudo_label_summary(r)) << ". Every number: <a href=\"results.json\">results.json</a>.</p>\n";
  b << "<h2>Table 3: macro F1 by training source</h2>\n" << table3_html(r);
  write_text_file(path("f1.svg"), f1_chart(r), force);
  written.push_back(path("f1.svg"));
  b << "<img src=\"f1.svg\" alt=\"macro F1 per training source with its spread\">\n";

  b << "<h2>Confusion matrices (summed over runs)</h2>\n<p class=\"note\">Rows: true label, "
       "columns: predicted; "
       "shading: share of the row (recall on the diagonal).</p>\n";
  std::vector<std::string> clusters;
  for (int c = 0; c < r.clusters; ++c) {
    std::string label = std::to_string(c);
    if (r.cluster_vs_category.rows() == r.clusters && !r.categories.empty()) {
      Eigen::Index best = 0;
      r.cluster_vs_category.row(c).maxCoeff(&best);
      label += " (" + r.categories[std::size_t(best)] + ")";
    }
    clusters.push_back(label);
  }
  b << "<div class=\"charts\">\n";
  for (const auto& s : r.sources)
    b << confusion_html(source_title(s.source) + ": pseudo labels", s.confusion, clusters);
  b << "</div>\n<div class=\"charts\">\n";
  for (const auto& s : r.sources)
    if (s.category_confusion.size() > 0)
      b << confusion_html(source_title(s.source) + ": categories", s.category_confusion,
                          r.categories);
  b << "</div>\n<p><img src=\"confusion.png\" alt=\"confusion matrices (PNG)\"></p>\n";

  b << "<h2>Per-class F1 (pseudo labels, mean over runs)</h2>\n<table "
       "id=\"class_f1\"><tr><th>cluster "
       "(windows)</th>";
  for (const auto& s : r.sources) b << "<th>" << html_escape(source_title(s.source)) << "</th>";
  b << "</tr>\n";
  for (int c = 0; c < r.clusters; ++c) {
    b << "<tr><td>" << html_escape(clusters[std::size_t(c)]) << " ("
      << (c < int(r.cluster_sizes.size()) ? r.cluster_sizes[std::size_t(c)] : 0) << ")</td>";
    for (const auto& s : r.sources)
      b << "<td class=\"num\">"
        << (c < int(s.class_f1_mean.size()) ? fixed_text(s.class_f1_mean[std::size_t(c)]) : "&ndash;")
        << "</td>";
    b << "</tr>\n";
  }
  b << "</table>\n";
  if (!r.categories.empty())
    b << "<p>Cluster purity against categories: " << fixed_text(r.cluster_purity) << ", adjusted Rand index "
      << fixed_text(r.cluster_ari) << "</p>\n";

  b << "<h2>Synthetic bodies</h2>\n<table><tr><th>id</th><th>sex</th><th>height "
       "(cm)</th><th>weight (kg)</th></tr>\n";
  for (const auto& body : r.synthetic_bodies)
    b << "<tr><td>" << html_escape(body.id) << "</td><td>" << sex_name(body.sex)
      << "</td><td class=\"num\">" << fixed_text(body.height_cm, 1) << "</td><td class=\"num\">"
      << fixed_text(body.weight_kg, 1) << "</td></tr>\n";
  b << "</table>\n<p class=\"note\">Time: " << fixed_text(r.seconds, 1) << " s.</p>\n";
  write_text_file(path("index.html"), html_page("ptnet HAR validation", b.str()), force);
  written.push_back(path("index.html"));
  return written;
}

}  // namespace ptnet::har
