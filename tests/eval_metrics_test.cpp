// Metrics on hand-computed cases (issue 5): a map against itself, known
// differences, constant ground truth, and the table recomputed from the CSV.
#include <gtest/gtest.h>

#include <cmath>

#include "core/csv.hpp"
#include "data_test_util.hpp"
#include "eval/eval_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"

namespace ptnet {
namespace {

PressureSequence blank(int frames) { return PressureSequence(MatSpec{4, 3, 0.02}, frames, 30); }

TEST(Metrics, MapAgainstItselfIsPerfect) {
  PressureSequence s = blank(2);
  s.at(0, 1, 1) = 10;
  s.at(0, 2, 1) = 20;
  s.at(1, 0, 0) = 5;
  const SequenceMetrics m = compare(s, s, {});
  EXPECT_DOUBLE_EQ(m.rmse_kpa, 0);
  EXPECT_DOUBLE_EQ(m.binary_r2, 1);
  EXPECT_DOUBLE_EQ(m.cop_error_cm, 0);
  EXPECT_EQ(m.cop_frames, 2);
  EXPECT_DOUBLE_EQ(m.force_error_pct, 0);
  EXPECT_DOUBLE_EQ(m.contact_iou, 1);
}

TEST(Metrics, RmseOfKnownDifference) {
  // 24 cells; two differ by 6 kPa: RMSE = sqrt(2 * 36 / 24) = sqrt(3).
  PressureSequence a = blank(2), b = blank(2);
  a.at(0, 0, 0) = 6;
  b.at(1, 3, 2) = 6;
  EXPECT_NEAR(rmse(a.kpa.data(), b.kpa.data(), a.kpa.size()), std::sqrt(3.0), 1e-12);
}

TEST(Metrics, BinaryR2OfKnownCase) {
  // Truth: 3 of 12 cells loaded, q = 0.25, SS_tot = 12 * 0.25 * 0.75 = 2.25.
  // Prediction misses one loaded cell and adds one: SS_res = 2.
  const float truth[12] = {1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const float pred[12] = {1, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_NEAR(binary_r2(pred, truth, 12, 0.5), 1.0 - 2.0 / 2.25, 1e-12);
  // Values only matter through the threshold.
  const float pred_scaled[12] = {9, 3, 0.2f, 7, 0, 0, 0, 0, 0.4f, 0, 0, 0};
  EXPECT_NEAR(binary_r2(pred_scaled, truth, 12, 0.5), 1.0 - 2.0 / 2.25, 1e-12);
}

TEST(Metrics, ConstantGroundTruthIsDefinedNeverNaN) {
  const float zeros[4] = {0, 0, 0, 0};
  const float one[4] = {0, 3, 0, 0};
  EXPECT_DOUBLE_EQ(binary_r2(zeros, zeros, 4, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(binary_r2(one, zeros, 4, 0.5), 0.0);
  const float full[4] = {2, 2, 2, 2};
  EXPECT_DOUBLE_EQ(binary_r2(full, full, 4, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(binary_r2(one, full, 4, 0.5), 0.0);
  PressureSequence a = blank(1), b = blank(1);
  const SequenceMetrics m = compare(a, b, {});
  EXPECT_FALSE(std::isnan(m.binary_r2));
  EXPECT_FALSE(std::isnan(m.cop_error_cm));
  EXPECT_EQ(m.cop_frames, 0);
  EXPECT_DOUBLE_EQ(m.contact_iou, 1.0);
  EXPECT_DOUBLE_EQ(m.force_error_pct, 0.0);
}

TEST(Metrics, CentreOfPressureForceAndIoU) {
  // One loaded cell moved by 3 rows and 1 column: CoP error = sqrt(10) cells.
  PressureSequence a = blank(1), b = blank(1);
  a.at(0, 0, 0) = 10;
  b.at(0, 3, 1) = 15;
  const SequenceMetrics m = compare(a, b, {});
  EXPECT_NEAR(m.cop_error_cm, std::sqrt(10.0) * 2.0, 1e-9);
  EXPECT_NEAR(m.force_error_pct, 5.0 / 15.0 * 100.0, 1e-9);
  EXPECT_DOUBLE_EQ(m.contact_iou, 0.0);
}

TEST(Metrics, WeightRatioBaselineScales) {
  PressureSequence s = blank(1);
  s.at(0, 1, 2) = 10;
  const PressureSequence scaled = weight_ratio_baseline(s, 50, 75);
  EXPECT_FLOAT_EQ(scaled.at(0, 1, 2), 15.0f);
  EXPECT_THROW(weight_ratio_baseline(s, 0, 75), Error);
}

TEST(Metrics, BodyScaleBaselineZoomsAboutTheCentreAndKeepsForceRatio) {
  // 80 x 28 mat, centre at (39.5, 13.5). A foot-sized 12 x 6 blob at rows
  // 54-65, cols 11-16 (centre 59.5, 13.5: 20 cells from the mat centre) on a
  // body 1.25 times as tall lands 25 cells from the centre; total force
  // scales with weight (up to the bilinear resampling of the blob's edges).
  PressureSequence s(MatSpec{}, 1, 30);
  for (int r = 54; r <= 65; ++r)
    for (int c = 11; c <= 16; ++c) s.at(0, r, c) = 100;
  const BodySpec a{"a", Sex::female, 160, 60}, b{"b", Sex::male, 200, 90};
  const PressureSequence z = body_scale_baseline(s, a, b);
  double force_in = 0, force_out = 0, row_moment = 0;
  for (int r = 0; r < 80; ++r)
    for (int c = 0; c < 28; ++c) {
      force_in += s.at(0, r, c);
      force_out += z.at(0, r, c);
      row_moment += z.at(0, r, c) * r;
    }
  EXPECT_NEAR(force_out / force_in, 90.0 / 60.0, 0.03);
  EXPECT_NEAR(row_moment / force_out, 39.5 + 1.25 * 20, 0.05);
  // Same height and weight: the identity.
  const PressureSequence same = body_scale_baseline(s, a, a);
  for (std::size_t i = 0; i < s.kpa.size(); ++i) ASSERT_FLOAT_EQ(same.kpa[i], s.kpa[i]);
  EXPECT_THROW(zoom_about_centre(s, 0.0, 1.0), Error);
}

TEST(Metrics, ShapeMismatchIsAnError) {
  EXPECT_THROW(compare(blank(1), blank(2), {}), Error);
}

// Each bad argument is named with its value (issue 24, probe defect 11): a
// NaN threshold made binary R^2 1, a NaN pitch "shapes differ (1 x 4 x 3 vs
// 1 x 4 x 3)", a negative pitch passed.
TEST(Metrics, BadArgumentsAreNamedWithTheirValue) {
  using testing_util::error_of;
  const float p[2] = {0, 2}, t[2] = {0, 2};
  const double nan = std::nan("");
  EXPECT_EQ(error_of([&] { binary_r2(p, t, 2, nan); }),
            "binary_r2: threshold_kpa: expected a finite number >= 0, found nan");
  EXPECT_EQ(error_of([&] { contact_iou(p, t, 2, -1); }),
            "contact_iou: threshold_kpa: expected a finite number >= 0, found -1");
  for (const double pitch : {nan, -1.0, 0.0}) {
    PressureSequence a = blank(1);
    a.mat.pitch_m = pitch;
    EXPECT_EQ(error_of([&] { compare(a, a, {}); }),
              "compare: pitch_m: expected a cell size > 0 m, found " + number_text(pitch));
  }
  PressureSequence b = blank(1);
  b.mat.pitch_m = 0.03;
  EXPECT_EQ(error_of([&] { compare(blank(1), b, {}); }), "compare: mats differ in pitch_m (0.02 vs 0.03 m)");
  EXPECT_EQ(error_of([&] { compare(blank(1), blank(1), MetricOptions{nan}); }),
            "binary_r2: threshold_kpa: expected a finite number >= 0, found nan");
  EXPECT_EQ(error_of([&] { zoom_about_centre(blank(1), 1.1, nan); }),
            "zoom: gain: expected a finite number >= 0, found nan");
  EXPECT_EQ(error_of([&] { zoom_about_centre(blank(1), nan, 1.0); }),
            "zoom: scale: expected a finite number > 0, found nan");
}

EvalRow row(const std::string& method, const std::string& category, int take, double rmse_kpa,
            double r2) {
  EvalRow r;
  r.method = method;
  r.category = category;
  r.take = take;
  r.motion_id = category + std::to_string(take);
  r.source_sequence = "s";
  r.target_sequence = "t";
  r.source_body = "o1";
  r.target_body = "o2";
  r.frames = 30;
  r.metrics.rmse_kpa = rmse_kpa;
  r.metrics.binary_r2 = r2;
  r.metrics.contact_iou = 0.5;
  return r;
}

TEST(Table, GroupMeansAndCsvRoundTrip) {
  std::vector<EvalRow> rows{row("model", "walking", 1, 2.0, 0.9), row("model", "walking", 1, 4.0, 0.7),
                            row("model", "rom", 1, 6.0, 0.5), row("copy", "walking", 1, 10.0, 0.4),
                            row("model", "acting", 2, 1.0, 0.95)};
  const auto groups = summarise(rows);
  auto get = [&](const std::string& method, const std::string& group, bool seen) {
    for (const auto& g : groups)
      if (g.method == method && g.group == group && g.seen == seen) return g;
    ADD_FAILURE() << "no group " << method << "/" << group;
    return GroupSummary{};
  };
  EXPECT_DOUBLE_EQ(get("model", "walking", true).mean.rmse_kpa, 3.0);
  EXPECT_DOUBLE_EQ(get("model", "average", true).mean.rmse_kpa, 4.0);
  EXPECT_NEAR(get("model", "average", true).mean.binary_r2, 0.7, 1e-12);
  EXPECT_DOUBLE_EQ(get("model", "average", false).mean.binary_r2, 0.95);

  // Recompute the whole table from the CSV: identical output.
  const std::string csv = format_metrics_csv(rows);
  const auto back = parse_metrics_csv(csv, "metrics.csv");
  ASSERT_EQ(back.size(), rows.size());
  EXPECT_EQ(format_table(back), format_table(rows));
  const std::string table = format_table(rows);
  EXPECT_NE(table.find("| walking | 2 | 3.00 | 0.800 |"), std::string::npos) << table;
  EXPECT_NE(table.find("Unseen motions"), std::string::npos);
}

// Names come from user files: a BVH "walk, fast.bvh", a body id that a
// spreadsheet would run as a formula. metrics.csv is RFC 4180 (every row
// has the header's 15 fields), no text field starts with = + - @, and every
// value reads back as it was.
TEST(Table, CsvQuotesAndNeutralisesUserText) {
  EvalRow r = row("model", "walking", 1, 2.0, 0.9);
  r.motion_id = "walk, fast";
  r.source_sequence = "walk, fast__\"o1\"";
  r.source_body = "=HYPERLINK(\"http://x\",\"y\")";
  r.target_body = "'+quoted";
  r.target_sequence = "line\nbreak";
  r.category = "-1+2";
  const std::string csv = format_metrics_csv({r, row("copy", "@rom", 2, 1.0, 0.5)});
  const CsvTable t = parse_csv(csv, "metrics.csv");
  ASSERT_EQ(t.header.size(), 15u);
  ASSERT_EQ(t.rows.size(), 2u);
  for (const CsvRow& row : t.rows)
    for (const std::string& f : row.fields)
      EXPECT_EQ(std::string("=+-@").find(f.empty() ? ' ' : f.front()), std::string::npos) << f;
  EXPECT_EQ(t.rows[0].fields[size_t(t.column("source_body"))], "'=HYPERLINK(\"http://x\",\"y\")");
  const auto back = parse_metrics_csv(csv, "metrics.csv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].motion_id, r.motion_id);
  EXPECT_EQ(back[0].source_sequence, r.source_sequence);
  EXPECT_EQ(back[0].source_body, r.source_body);
  EXPECT_EQ(back[0].target_body, r.target_body);
  EXPECT_EQ(back[0].target_sequence, r.target_sequence);
  EXPECT_EQ(back[0].category, r.category);
  EXPECT_EQ(back[1].category, "@rom");
  EXPECT_EQ(back[0].metrics.rmse_kpa, 2.0);
}

TEST(Table, MalformedCsvNamesFileAndLine) {
  try {
    parse_metrics_csv(format_metrics_csv({}) + "model,x\n", "m.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "m.csv:2: expected 15 fields (as the header), found 2");
  }
}

}  // namespace
}  // namespace ptnet
