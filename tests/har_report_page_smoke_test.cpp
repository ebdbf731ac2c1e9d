// The HAR report page (issue 16) in a real browser: har/index.html of a
// hand-made result (3 sources, 3 clusters, 2 categories) and of a real
// `ptnet validate-har` run on a small dataset load headless from file://
// with every image and chart, Table 3's cells equal results.json (mean +-
// std), and screenshots are saved in the build folder
// (har_report_page.png, har_report_page_cli.png). Skips only where chromium
// is not installed.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "browser_test_util.hpp"
#include "cli_test_util.hpp"
#include "data_test_util.hpp"
#include "ptnet/har.hpp"
#include "ptnet/io.hpp"
#include "report_test_util.hpp"

namespace ptnet::har {
namespace {

namespace fs = std::filesystem;

HarResult hand_made_result() {
  HarResult r;
  r.dataset = "real <recordings>.h5";  // escaped on the page
  r.train_subjects = {"s1", "s2", "s3"};
  r.test_subjects = {"s4"};
  r.runs = 3;
  r.stride = 5;
  r.train_windows = 300, r.test_windows = 90;
  r.pca_components = 4, r.pca_explained = 0.83;
  r.bandwidth = 1.25;
  r.clusters = 3;
  r.cluster_sizes = {150, 140, 100};
  r.categories = {"acting", "walking"};
  r.cluster_vs_category.resize(3, 2);
  r.cluster_vs_category << 10, 140, 120, 20, 90, 10;
  r.cluster_purity = 0.9;
  r.synthetic_bodies = {BodySpec{"syn1", Sex::female, 160, 55, "retargeted"},
                        BodySpec{"syn2", Sex::male, 182, 88, "retargeted"}};
  int k = 0;
  for (const char* source : {"real", "synthetic", "real+synthetic"}) {
    SourceResult s;
    s.source = source;
    s.train_windows = 300 * (k + 1);
    s.macro_f1 = {0.61 + 0.05 * k, 0.64 + 0.05 * k, 0.58 + 0.05 * k};
    s.macro_f1_mean = 0.61 + 0.05 * k;
    s.macro_f1_std = 0.03;
    s.accuracy = {0.7, 0.72, 0.69};
    s.accuracy_mean = 0.7033;
    s.class_f1_mean = {0.5, 0.6, 0.7};
    s.confusion.resize(3, 3);
    s.confusion << 80, 10, 0, 5, 70, 15, 0, 20, 70;
    s.category_macro_f1 = {0.8, 0.82, 0.78};
    s.category_macro_f1_mean = 0.8;
    s.category_macro_f1_std = 0.02 + 0.001 * k;
    s.category_confusion.resize(2, 2);
    s.category_confusion << 40, 5, 6, 39;
    r.sources.push_back(s);
    ++k;
  }
  r.seconds = 12.5;
  return r;
}

std::string spread(const nlohmann::json& x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f \xc2\xb1 %.3f", x["mean"].get<double>(),
                x["std"].get<double>());
  return buf;
}

// Table 3's cells on the loaded page equal results.json.
void check_table3(const std::string& dom, const std::string& results_path) {
  const auto results = nlohmann::json::parse(read_text_file(results_path));
  const auto cells = testing_browser::data_cells(dom, {"data-source", "data-metric"});
  ASSERT_EQ(cells.size(), 9u);  // 3 sources x (macro F1, category macro F1, accuracy)
  for (const auto& s : results["sources"]) {
    const std::string source = s["source"];
    EXPECT_EQ(cells.at(source + "|macro_f1"), spread(s["macro_f1"])) << source;
    EXPECT_EQ(cells.at(source + "|category_macro_f1"), spread(s["category_macro_f1"])) << source;
    char acc[32];
    std::snprintf(acc, sizeof acc, "%.3f", s["accuracy"]["mean"].get<double>());
    EXPECT_EQ(cells.at(source + "|accuracy"), acc) << source;
  }
}

TEST(HarReportPage, LoadsInChromiumWithTable3EqualToResultsJson) {
  testing_util::TempDir dir("har_page");
  const HarResult r = hand_made_result();
  write_text_file(dir.file("results.json"), to_json(r), false);
  write_confusion_png(dir.file("confusion.png"), r, false);
  const auto written = write_html_report(dir.path.string(), r, false);
  ASSERT_EQ(written.back(), dir.file("index.html"));
  const std::string html = read_text_file(dir.file("index.html"));
  EXPECT_NE(html.find("real &lt;recordings&gt;.h5"), std::string::npos);
  // Refuses to overwrite without force.
  EXPECT_THROW(write_html_report(dir.path.string(), r, false), Error);

  const std::string chromium = testing_browser::find_chromium();
  if (chromium.empty()) GTEST_SKIP() << testing_browser::kNoChromium;
  const fs::path shot = fs::path(PTNET_BINARY).parent_path() / "har_report_page.png";
  const auto load = testing_browser::load_page(chromium, dir.file("index.html"), shot);
  ASSERT_EQ(load.status, 0) << load.log;
  EXPECT_EQ(load.ok, "yes") << "failures: " << load.failures;
  EXPECT_EQ(load.images, 2);  // f1.svg, confusion.png
  EXPECT_TRUE(load.console.empty()) << load.console.front();
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 10000) << "no screenshot at " << shot;

  check_table3(load.dom, dir.file("results.json"));
  // The confusion matrices as tables: 3 pseudo-label and 3 category ones.
  std::size_t tables = 0;
  for (std::size_t at = load.dom.find("class=\"confusion\""); at != std::string::npos;
       at = load.dom.find("class=\"confusion\"", at + 1))
    ++tables;
  EXPECT_EQ(tables, 6u);
}

TEST(HarReportPage, ValidateHarWritesThePageAndItLoads) {
  testing_util::TempDir dir("har_page_cli");
  const std::string data = dir.file("real.h5"), out = dir.file("har");
  testing::write_report_dataset(data);
  const auto run = testing_cli::run_ptnet(
      "validate-har --real '" + data +
          "' --baseline copy --train-subjects r0,r1,r2 "
          "--test-subjects o4,o5 --runs 2 --epochs 2 --synthetic-bodies 2 --stride 10 "
          "--out '" +
          out + "'",
      dir.path / "har");
  ASSERT_EQ(run.status, 0) << run.err;
  const fs::path page = fs::path(out) / "index.html";
  EXPECT_NE(run.out.find("open " + page.string() + " in a browser"), std::string::npos) << run.out;
  ASSERT_TRUE(fs::exists(page));

  const std::string chromium = testing_browser::find_chromium();
  if (chromium.empty()) GTEST_SKIP() << testing_browser::kNoChromium;
  const auto load = testing_browser::load_page(
      chromium, page, fs::path(PTNET_BINARY).parent_path() / "har_report_page_cli.png");
  ASSERT_EQ(load.status, 0) << load.log;
  EXPECT_EQ(load.ok, "yes") << "failures: " << load.failures;
  EXPECT_EQ(load.images, 2);
  EXPECT_TRUE(load.console.empty()) << load.console.front();
  check_table3(load.dom, (fs::path(out) / "results.json").string());
}

}  // namespace
}  // namespace ptnet::har
