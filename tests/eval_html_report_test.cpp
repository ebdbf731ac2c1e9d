// report/index.html without a browser (issue 16): the page is driven by the
// methods the rows hold (a noise floor appears by itself), text is escaped,
// and the training curve comes from the model folder's history.csv.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../src/eval/html_report.hpp"  // internal to the eval stage
#include "data_test_util.hpp"
#include "eval/eval_internal.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
namespace {

using testing_util::TempDir;

EvalRow row(const std::string& method, const std::string& category, int take, double rmse) {
  EvalRow r;
  r.method = method;
  r.motion_id = category + "<1>";
  r.category = category;
  r.take = take;
  r.source_sequence = "a", r.target_sequence = "b";
  r.source_body = "o1", r.target_body = "o2";
  r.frames = 30;
  r.metrics.rmse_kpa = rmse;
  r.metrics.binary_r2 = 0.5;
  return r;
}

TEST(EvalHtmlReport, EveryMethodInTheRowsGetsItsColumnsAndBars) {
  TempDir dir("html_report");
  std::vector<EvalRow> rows;
  for (const char* m : {"model", "copy", "floor"}) {
    rows.push_back(row(m, "walking", 1, 2.0));
    rows.push_back(row(m, "walking", 2, 3.0));
  }
  ReportOptions o;
  o.out_dir = dir.path.string();
  const auto written = write_report_html(rows, {}, {{rows[0], "worst_1.png", ""}}, "d<ata>.h5", o);
  EXPECT_EQ(written.size(), 5u);  // 4 charts + index.html (no model folder)
  const std::string page = read_text_file(dir.file("index.html"));
  EXPECT_NE(page.find("<th colspan=\"2\">noise floor</th>"), std::string::npos);
  EXPECT_NE(page.find("data-method=\"floor\" data-group=\"walking\" data-split=\"unseen\" "
                      "data-metric=\"rmse_kpa\">3.00<"),
            std::string::npos);
  EXPECT_NE(read_text_file(dir.file("chart_rmse_kpa_seen.svg")).find("noise floor: 2"),
            std::string::npos);
  EXPECT_NE(page.find("d&lt;ata&gt;.h5"), std::string::npos);
  EXPECT_EQ(page.find("walking<1>"), std::string::npos) << "unescaped text";
  EXPECT_NE(page.find("No model folder given."), std::string::npos);
}

// Only comparable numbers on one axis: the paper's RMSE is in its sensor's
// units, so its bars are on the binary R^2 charts only (before, the RMSE
// charts put them on the kPa axis), and its table column says so.
TEST(EvalHtmlReport, ThePapersRmseIsOnNoKpaAxis) {
  TempDir dir("html_report_units");
  std::vector<EvalRow> rows;
  for (const char* m : {"model", "model_raw", "copy", "weight_ratio", "body_scale", "floor"})
    for (int take : {1, 2}) rows.push_back(row(m, "walking", take, 2.0));
  ReportOptions o;
  o.out_dir = dir.path.string();
  write_report_html(rows, {}, {}, "d.h5", o);
  for (const char* split : {"seen", "unseen"}) {
    const std::string rmse = read_text_file(dir.file(std::string("chart_rmse_kpa_") + split + ".svg"));
    const std::string r2 = read_text_file(dir.file(std::string("chart_binary_r2_") + split + ".svg"));
    EXPECT_EQ(rmse.find(">paper<"), std::string::npos) << split;
    EXPECT_EQ(rmse.find(", paper: "), std::string::npos) << split;
    EXPECT_NE(r2.find(">paper<"), std::string::npos) << split;
    EXPECT_NE(r2.find(std::string("walking, paper: ") + (split == std::string("seen") ? "0.81" : "0.71")),
              std::string::npos)
        << split;
  }
  const std::string page = read_text_file(dir.file("index.html"));
  EXPECT_NE(page.find("<th>RMSE (its units)</th>"), std::string::npos);
}

TEST(EvalHtmlReport, TrainingCurveFromHistoryCsvAndTheConfig) {
  TempDir dir("html_report_model");
  std::filesystem::create_directories(dir.path / "model");
  std::ofstream(dir.path / "model" / "history.csv")
      << "epoch,train_loss,val_loss,lr,seconds\n1,0.5,0.6,0.002,1\n"
         "2,0.3,0.4,0.002,1\n";
  std::ofstream(dir.path / "model" / "config.json") << "{\"format\": \"<ptnet-model>\"}\n";
  std::filesystem::create_directories(dir.path / "report");
  ReportOptions o;
  o.out_dir = (dir.path / "report").string();
  o.model_dir = (dir.path / "model").string();
  write_report_html({row("model", "rom", 1, 1.0)}, {}, {}, "d.h5", o);
  const std::string curve = read_text_file((dir.path / "report" / "training_curve.svg").string());
  EXPECT_NE(curve.find("<title>validation at 2: 0.4</title>"), std::string::npos);
  const std::string page = read_text_file((dir.path / "report" / "index.html").string());
  EXPECT_NE(page.find("src=\"training_curve.svg\""), std::string::npos);
  EXPECT_NE(page.find("&quot;format&quot;: &quot;&lt;ptnet-model&gt;&quot;"), std::string::npos);
  // A history without the loss columns is a one-line error naming the file.
  std::ofstream(dir.path / "model" / "history.csv") << "epoch,loss\n1,0.5\n";
  o.force = true;
  try {
    write_report_html({row("model", "rom", 1, 1.0)}, {}, {}, "d.h5", o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("history.csv:1: expected a header with column train_loss (epoch,train_loss,val_loss)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ptnet
