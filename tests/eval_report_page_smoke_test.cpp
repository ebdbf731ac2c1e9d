// The evaluation report page (issue 16) in a real browser: a tiny model
// (1 epoch) on a small synthetic dataset, `ptnet evaluate` writes report/,
// headless chromium loads report/index.html from file://: every image and
// chart loads, no console error, Table 2's cells equal the means of
// metrics.csv, and a screenshot is saved in the build folder
// (report_page.png). Skips only where chromium is not installed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "browser_test_util.hpp"
#include "cli_test_util.hpp"
#include "data_test_util.hpp"
#include "eval/eval_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/io.hpp"
#include "ptnet/train.hpp"
#include "report_test_util.hpp"
#include "train_synthetic.hpp"

namespace ptnet {
namespace {

namespace fs = std::filesystem;
using testing_util::TempDir;

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// Table 2's cells computed here from metrics.csv alone: per method, category
// (and "average") and split, the mean of each metric over the pairs, printed
// with the table's digits. Keys as data_cells() makes them.
std::map<std::string, std::string> expected_cells(const std::vector<EvalRow>& rows) {
  struct Sum {
    int n = 0;
    double rmse = 0, r2 = 0, cop = 0, force = 0, iou = 0;
  };
  std::map<std::string, Sum> sums;
  for (const auto& r : rows) {
    const std::string split = r.take == 1 ? "seen" : "unseen";
    for (const std::string& group : {r.category, std::string("average")}) {
      Sum& s = sums[r.method + "|" + group + "|" + split];
      ++s.n;
      s.rmse += r.metrics.rmse_kpa, s.r2 += r.metrics.binary_r2, s.cop += r.metrics.cop_error_cm;
      s.force += r.metrics.force_error_pct, s.iou += r.metrics.contact_iou;
    }
  }
  std::map<std::string, std::string> cells;
  for (const auto& [key, s] : sums) {
    cells[key + "|rmse_kpa"] = fixed(s.rmse / s.n, 2);
    cells[key + "|binary_r2"] = fixed(s.r2 / s.n, 3);
    if (key.rfind("model|", 0) == 0) {
      cells[key + "|rows"] = std::to_string(s.n);
      cells[key + "|cop_error_cm"] = fixed(s.cop / s.n, 2);
      cells[key + "|force_error_pct"] = fixed(s.force / s.n, 1);
      cells[key + "|contact_iou"] = fixed(s.iou / s.n, 3);
    }
  }
  return cells;
}

// In a page holding a chart's SVG inline: "fits" when every <text> (but the
// rotated axis label) lies within the SVG and overlaps no other, else what
// does not.
constexpr const char* kFitScript = R"js(
var svg = document.querySelector('svg'), w = svg.width.baseVal.value, bad = [];
var texts = Array.prototype.filter.call(svg.querySelectorAll('text'), function (t) { return !t.getAttribute('transform'); });
var boxes = texts.map(function (t) { return t.getBBox(); });
boxes.forEach(function (b, i) {
  if (b.x < 0 || b.x + b.width > w) bad.push('cut: ' + texts[i].textContent);
  for (var j = 0; j < i; ++j) {
    var c = boxes[j];
    if (b.x < c.x + c.width && c.x < b.x + b.width && b.y < c.y + c.height && c.y < b.y + b.height)
      bad.push('over: ' + texts[i].textContent + ' / ' + texts[j].textContent);
  }
});
document.getElementById('fit').textContent = bad.length ? bad.join('; ') : 'fits';
)js";

TEST(ReportPage, LoadsInChromiumWithTable2EqualToMetricsCsv) {
  TempDir dir("report_page");
  const std::string data = dir.file("data.h5"), model = dir.file("model"),
                    report = dir.file("report");
  testing::write_report_dataset(data);
  const auto source = open_dataset_source(data);
  train(*source, model, testing::synth_options(/*epochs=*/1));

  const auto run = testing_cli::run_ptnet(
      "evaluate --model '" + model + "' --data '" + data + "' --out '" + report + "' --stride 10",
      dir.path / "evaluate");
  ASSERT_EQ(run.status, 0) << run.err;
  const fs::path page = fs::path(report) / "index.html";
  EXPECT_NE(run.out.find("open " + page.string() + " in a browser"), std::string::npos) << run.out;
  ASSERT_TRUE(fs::exists(page));
  for (const char* category : testing::kReportCategories)
    for (const char* ext : {".png", ".gif"})
      EXPECT_TRUE(fs::exists(fs::path(report) / (std::string("qualitative_") + category + ext)))
          << category << ext;
  for (int i = 1; i <= 5; ++i)
    EXPECT_TRUE(fs::exists(fs::path(report) / ("worst_" + std::to_string(i) + ".png")));
  EXPECT_TRUE(fs::exists(fs::path(report) / "training_curve.svg"));

  const std::string chromium = testing_browser::find_chromium();
  if (chromium.empty()) GTEST_SKIP() << testing_browser::kNoChromium;
  const fs::path shot = fs::path(PTNET_BINARY).parent_path() / "report_page.png";
  const auto load = testing_browser::load_page(chromium, page, shot);
  ASSERT_EQ(load.status, 0) << load.log;
  EXPECT_EQ(load.ok, "yes") << "failures: " << load.failures;
  // 4 charts, 4 stills + 4 GIFs, 5 worst pairs, the training curve.
  EXPECT_EQ(load.images, 18);
  EXPECT_TRUE(load.console.empty()) << load.console.front();
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 10000)
      << "no screenshot at " << shot << "\n"
      << load.log;

  // Every text of every chart inside the chart, none over another, as the
  // browser lays it out (before: the RMSE chart's legend was cut at "noise
  // fl" and its paper entry was beyond the edge).
  for (const auto& e : fs::directory_iterator(report)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() != ".svg") continue;
    const fs::path wrapper = dir.path / (name + ".html");
    std::ofstream(wrapper) << "<!DOCTYPE html><html><body>" << read_text_file(e.path().string())
                           << "<pre id=\"fit\"></pre><script>" << kFitScript << "</script></body></html>";
    const auto fit = testing_browser::run_chromium(chromium, wrapper, dir.path / "fit", "--dump-dom");
    const std::string mark = "<pre id=\"fit\">";
    const auto at = fit.out.find(mark);
    ASSERT_NE(at, std::string::npos) << name << ": " << fit.err.substr(0, 500);
    const auto start = at + mark.size();
    EXPECT_EQ(fit.out.substr(start, fit.out.find("</pre>", start) - start), "fits") << name;
  }

  const auto rows =
      parse_metrics_csv(read_text_file((fs::path(report) / "metrics.csv").string()), "metrics.csv");
  const auto expected = expected_cells(rows);
  auto cells = testing_browser::data_cells(
      load.dom, {"data-method", "data-group", "data-split", "data-metric"});
  // The paper's figures come from metrics.json, the rest from metrics.csv.
  const auto paper = nlohmann::json::parse(
      read_text_file((fs::path(report) / "metrics.json").string()))["paper_table2"];
  int paper_cells = 0;
  for (auto it = cells.begin(); it != cells.end();) {
    if (it->first.rfind("paper|", 0) != 0) {
      ++it;
      continue;
    }
    std::string group = it->first.substr(6, it->first.find('|', 6) - 6);
    const bool seen = it->first.find("|seen|") != std::string::npos;
    const bool rmse = it->first.find("|rmse_kpa") != std::string::npos;
    const auto& split = paper[seen ? "seen" : "unseen"];
    EXPECT_EQ(it->second, split.contains(group) ? fixed(split[group][rmse ? 0 : 1].get<double>(), 2)
                                                : "\xe2\x80\x93")
        << it->first;
    ++paper_cells;
    it = cells.erase(it);
  }
  EXPECT_EQ(paper_cells, 2 * 2 * 5);  // 2 metrics x 2 splits x (4 categories + average)
  EXPECT_EQ(cells.size(), expected.size());
  for (const auto& [key, text] : expected) {
    auto it = cells.find(key);
    if (it == cells.end())
      ADD_FAILURE() << "no cell " << key << " on the page";
    else
      EXPECT_EQ(it->second, text) << key;
  }
}

}  // namespace
}  // namespace ptnet
