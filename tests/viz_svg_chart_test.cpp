// SVG charts and HTML helpers of the report pages (viz.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <regex>
#include <set>

#include "ptnet/error.hpp"
#include "ptnet/viz.hpp"

namespace ptnet {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Html, EscapesTheFiveSpecialCharacters) {
  EXPECT_EQ(html_escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
  EXPECT_EQ(html_escape("plain"), "plain");
}

TEST(Html, PageHasTheTitleEscapedAndTheCheckScript) {
  const std::string page = html_page("a < b", "<p>x</p>");
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("<title>a &lt; b</title>"), std::string::npos);
  EXPECT_NE(page.find("<p>x</p>"), std::string::npos);
  EXPECT_NE(page.find("dataset.ok"), std::string::npos);
  EXPECT_EQ(page.find("http://"), std::string::npos) << "nothing from the network";
  EXPECT_EQ(page.find("https://"), std::string::npos) << "nothing from the network";
}

TEST(SvgBarChart, OneBarPerFiniteValueWithItsValueInTheTooltip) {
  BarChart c;
  c.title = "RMSE <seen>";
  c.groups = {"walking", "rom", "average"};
  c.series = {{"model", {1.5, 2.25, NAN}, {}}, {"copy", {3, 4, 3.5}, {0.5, 0.5, 0.5}}};
  const std::string svg = svg_bar_chart(c);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"300\"", 0),
            0u);
  EXPECT_EQ(count(svg, "<rect x="), 5u + 2u);  // 5 bars + 2 legend boxes
  EXPECT_NE(svg.find("<title>rom, model: 2.25</title>"), std::string::npos);
  EXPECT_NE(svg.find("RMSE &lt;seen&gt;"), std::string::npos);
  EXPECT_EQ(count(svg, "<path d="), 3u);  // whiskers of the copy bars
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

// A legend wider than the chart wraps onto more rows above a lower plot, so
// that no entry runs past the chart (before, the report's 600 px RMSE chart
// showed "noise fl" and no paper). Width: 7.5 px a character at 12 px, the
// widest DejaVu Sans gives in chromium (eval_report_page_smoke_test checks
// the real text in the browser).
TEST(SvgBarChart, ALongLegendWrapsWithinTheChart) {
  BarChart c;
  c.width = 600;
  c.groups = {"walking", "average"};
  for (const char* name : {"model", "model (raw)", "copy", "weight ratio", "body scale", "noise floor", "paper"})
    c.series.push_back({name, {1, 2}, {}});
  const std::string svg = svg_bar_chart(c);
  std::set<double> rows;
  for (const auto& series : c.series) {
    const std::string tag = ">" + series.name + "</text>";
    const auto end = svg.find(tag);
    ASSERT_NE(end, std::string::npos) << series.name << " is not in the legend";
    const auto start = svg.rfind("<text x=\"", end);
    double x = 0, y = 0;
    ASSERT_EQ(std::sscanf(svg.c_str() + start, "<text x=\"%lf\" y=\"%lf\"", &x, &y), 2);
    EXPECT_LE(x + 7.5 * double(series.name.size()), 600 - 16) << series.name;
    rows.insert(y);
  }
  EXPECT_EQ(rows.size(), 2u);
  // The plot starts below the second row: the top grid line is at 56 + 18.
  EXPECT_NE(svg.find("y1=\"74.00\""), std::string::npos) << svg.substr(0, 3000);
  // A chart too short for its legend is an error, not a cut legend.
  c.height = 56 + 40 + 30;
  EXPECT_THROW(svg_bar_chart(c), Error);
}

TEST(SvgBarChart, NegativeValuesGetAZeroLineAndBarsBelowIt) {
  BarChart c;
  c.groups = {"a"};
  c.series = {{"r2", {-0.4}, {}}};
  const std::string svg = svg_bar_chart(c);
  EXPECT_NE(svg.find(">-0.4<"), std::string::npos) << svg;  // the axis reaches below zero
  EXPECT_NE(svg.find(">0.0<"), std::string::npos) << svg;
}

TEST(SvgBarChart, MismatchedSeriesIsAnError) {
  BarChart c;
  c.title = "t";
  c.groups = {"a", "b"};
  c.series = {{"s", {1}, {}}};
  EXPECT_THROW(svg_bar_chart(c), Error);
}

TEST(SvgLineChart, TrainAndValidationCurvesWithWholeEpochTicks) {
  LineChart c;
  c.x_label = "epoch";
  c.series = {{"train", {1, 2, 3}, {0.5, 0.3, 0.2}}, {"validation", {1, 2, 3}, {0.6, 0.4, 0.35}}};
  const std::string svg = svg_line_chart(c);
  EXPECT_EQ(count(svg, "<circle"), 6u);
  EXPECT_EQ(count(svg, "stroke-width=\"2\" fill=\"none\""), 2u);
  EXPECT_NE(svg.find(">2<"), std::string::npos);
  EXPECT_EQ(svg.find(">1.5<"), std::string::npos) << "no fractional epochs";
  EXPECT_NE(svg.find("<title>validation at 3: 0.35</title>"), std::string::npos);
}

TEST(SvgLineChart, OneEpochIsOnePointInTheMiddle) {
  LineChart c;
  c.series = {{"train", {1}, {0.5}}};
  const std::string svg = svg_line_chart(c);
  EXPECT_EQ(count(svg, "<circle"), 1u);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("<circle cx=\"([0-9.]+)\"")));
  EXPECT_NEAR(std::stod(m[1]), (64 + 640 - 16) / 2.0, 1);
}

}  // namespace
}  // namespace ptnet
