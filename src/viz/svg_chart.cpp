// SVG charts for the report pages: grouped bars and lines (viz.hpp).
//
// Layout in px: a title line on top, the legend under it (as many rows as
// its entries need to fit the width), the plot area between a left margin
// (y tick labels, y label) and a bottom margin (x labels). Every value is
// also in a <title> of its mark (hover tooltip).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/viz.hpp"
#include "viz/viz_internal.hpp"

namespace ptnet {
namespace {

constexpr int kLeft = 64;  // y tick labels and y label
constexpr int kRight = 16;
constexpr int kTop = 56;     // title and one row of legend
constexpr int kLegendRow = 18;  // each further row of legend
constexpr int kBottom = 40;  // x labels
// Legend text width, px per character at 12 px: DejaVu Sans in chromium
// measured 5.7-7.5 (narrow "floor", wide "model"); the upper end, so a row
// never runs past the chart.
constexpr double kCharPx = 7.5;
constexpr int kFontPx = 12;
constexpr const char* kAxisInk = "#555555";
constexpr const char* kGridInk = "#e4e4e4";

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string tick_text(double v, double step) {
  char buf[32];
  const int digits = step >= 1 ? 0 : int(std::ceil(-std::log10(step) - 1e-9));
  std::snprintf(buf, sizeof buf, "%.*f", std::min(digits, 6), std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buf;
}

std::string value_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// An axis range [lo, hi] covering the values (and 0 when with_zero), in whole ticks.
struct Axis {
  double lo = 0, hi = 1, step = 0.2;
  double px(double v, double px_lo, double px_hi) const {
    return px_lo + (v - lo) / (hi - lo) * (px_hi - px_lo);
  }
};

Axis make_axis(double lo, double hi, bool with_zero) {
  if (with_zero) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  if (!(hi > lo)) hi = lo + (lo == 0 ? 1 : std::abs(lo) * 0.1);
  Axis a;
  a.step = nice_step((hi - lo) / 5);
  a.lo = std::floor(lo / a.step + 1e-9) * a.step;
  a.hi = std::ceil(hi / a.step - 1e-9) * a.step;
  return a;
}

struct Frame {
  int width, height;
  double x0, x1, y0, y1;  // plot area (y0 top)
};

// Where each legend entry goes: its x and its row, entries packed left to
// right and wrapped before they would pass the chart's right margin.
struct LegendPlace {
  double x;
  int row;
};
std::vector<LegendPlace> legend_places(const std::vector<std::string>& names, int width) {
  std::vector<LegendPlace> out;
  double x = kLeft;
  int row = 0;
  for (const std::string& name : names) {
    const double w = 18 + kCharPx * double(name.size());  // the key, a gap, the text
    if (x > kLeft && x + w > width - kRight) x = kLeft, ++row;
    out.push_back({x, row});
    x += w + 18;
  }
  return out;
}
int legend_rows(const std::vector<std::string>& names, int width) {
  const auto places = legend_places(names, width);
  return places.empty() ? 1 : places.back().row + 1;
}

std::ostringstream open_svg(const Frame& f, const std::string& title) {
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f.width << "\" height=\"" << f.height
    << "\" viewBox=\"0 0 " << f.width << " " << f.height
    << "\" font-family=\"sans-serif\" font-size=\"" << kFontPx << "\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n"
    << "<text x=\"" << f.x0 << "\" y=\"18\" font-size=\"14\" font-weight=\"bold\">"
    << html_escape(title) << "</text>\n";
  return o;
}

void legend(std::ostringstream& o, const Frame& f, const std::vector<std::string>& names,
            bool lines) {
  const auto places = legend_places(names, f.width);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string c = chart_colour(int(i));
    const double x = places[i].x, y = 30 + kLegendRow * places[i].row;  // the key's top
    if (lines)
      o << "<line x1=\"" << num(x) << "\" y1=\"" << num(y + 6) << "\" x2=\"" << num(x + 14) << "\" y2=\""
        << num(y + 6) << "\" stroke=\"" << c << "\" stroke-width=\"2.5\"/>\n";
    else
      o << "<rect x=\"" << num(x) << "\" y=\"" << num(y) << "\" width=\"12\" height=\"12\" fill=\"" << c
        << "\"/>\n";
    o << "<text x=\"" << num(x + 18) << "\" y=\"" << num(y + 10) << "\">" << html_escape(names[i]) << "</text>\n";
  }
}

// Grid lines, tick labels and the y label of a vertical value axis.
void y_axis(std::ostringstream& o, const Frame& f, const Axis& a, const std::string& label) {
  for (double v = a.lo; v <= a.hi + a.step * 1e-6; v += a.step) {
    const double y = a.px(v, f.y1, f.y0);
    o << "<line x1=\"" << f.x0 << "\" y1=\"" << num(y) << "\" x2=\"" << f.x1 << "\" y2=\"" << num(y)
      << "\" stroke=\"" << (std::abs(v) < a.step * 1e-6 ? kAxisInk : kGridInk) << "\"/>\n"
      << "<text x=\"" << f.x0 - 6 << "\" y=\"" << num(y + 4) << "\" text-anchor=\"end\" fill=\""
      << kAxisInk << "\">" << tick_text(v, a.step) << "</text>\n";
  }
  const double cy = (f.y0 + f.y1) / 2;
  o << "<text x=\"14\" y=\"" << num(cy) << "\" text-anchor=\"middle\" transform=\"rotate(-90 14 "
    << num(cy) << ")\" fill=\"" << kAxisInk << "\">" << html_escape(label) << "</text>\n";
}

// The plot area of a chart of this size, inside the margins, below a
// legend of `rows` rows.
Frame chart_frame(int width, int height, int rows) {
  const double top = kTop + kLegendRow * (rows - 1);
  return {width, height, double(kLeft), double(width - kRight), top, double(height - kBottom)};
}

// The SVG opened with its title, the series' legend and the y axis.
template <typename Series>
std::ostringstream open_chart(const Frame& f, const std::string& title, const std::vector<Series>& series,
                              bool lines, const Axis& a, const std::string& y_label) {
  std::ostringstream o = open_svg(f, title);
  std::vector<std::string> names;
  for (const auto& s : series) names.push_back(s.name);
  legend(o, f, names, lines);
  y_axis(o, f, a, y_label);
  return o;
}

// A frame with room for a plot under its legend of `rows` rows.
template <typename Series>
Frame checked_frame(int width, int height, const std::vector<Series>& series) {
  std::vector<std::string> names;
  for (const auto& s : series) names.push_back(s.name);
  const int rows = width < kLeft + kRight + 40 ? 1 : legend_rows(names, width);
  const Frame f = chart_frame(width, height, rows);
  if (width < kLeft + kRight + 40 || f.y1 - f.y0 < 40)
    throw Error("chart: " + std::to_string(width) + " x " + std::to_string(height) + " px is too small" +
                (rows > 1 ? " for its legend of " + std::to_string(rows) + " rows" : std::string()));
  return f;
}

}  // namespace

std::string chart_colour(int i) {
  // Okabe-Ito: distinguishable with the common colour-vision deficiencies.
  static const char* const kPalette[] = {"#0072b2", "#e69f00", "#009e73", "#cc79a7",
                                         "#56b4e9", "#d55e00", "#f0e442", "#000000"};
  return kPalette[std::size_t(i) % (sizeof kPalette / sizeof *kPalette)];
}

std::string svg_bar_chart(const BarChart& c) {
  const Frame f = checked_frame(c.width, c.height, c.series);
  double lo = 0, hi = 0;
  for (const auto& s : c.series) {
    if (s.values.size() != c.groups.size())
      throw Error("chart '" + c.title + "': series '" + s.name + "' has " +
                  std::to_string(s.values.size()) + " values for " +
                  std::to_string(c.groups.size()) + " groups");
    for (std::size_t g = 0; g < s.values.size(); ++g) {
      const double v = s.values[g],
                   e = g < s.errors.size() && std::isfinite(s.errors[g]) ? s.errors[g] : 0;
      if (!std::isfinite(v)) continue;
      lo = std::min(lo, v - e);
      hi = std::max(hi, v + e);
    }
  }
  const Axis a = make_axis(lo, hi, true);
  std::ostringstream o = open_chart(f, c.title, c.series, /*lines=*/false, a, c.y_label);
  const double group_w = (f.x1 - f.x0) / double(std::max<std::size_t>(1, c.groups.size()));
  const double bar_w = group_w * 0.8 / double(std::max<std::size_t>(1, c.series.size()));
  const double zero = a.px(0, f.y1, f.y0);
  for (std::size_t g = 0; g < c.groups.size(); ++g) {
    const double gx = f.x0 + group_w * double(g);
    o << "<text x=\"" << num(gx + group_w / 2) << "\" y=\"" << num(f.y1 + 18)
      << "\" text-anchor=\"middle\">" << html_escape(c.groups[g]) << "</text>\n";
    for (std::size_t s = 0; s < c.series.size(); ++s) {
      const double v = c.series[s].values[g];
      if (!std::isfinite(v)) continue;
      const double x = gx + group_w * 0.1 + bar_w * double(s), y = a.px(v, f.y1, f.y0);
      o << "<rect x=\"" << num(x) << "\" y=\"" << num(std::min(y, zero)) << "\" width=\""
        << num(bar_w * 0.92) << "\" height=\"" << num(std::abs(zero - y)) << "\" fill=\""
        << chart_colour(int(s)) << "\"><title>"
        << html_escape(c.groups[g] + ", " + c.series[s].name + ": " + value_text(v))
        << "</title></rect>\n";
      const auto& errors = c.series[s].errors;
      if (g < errors.size() && std::isfinite(errors[g]) && errors[g] > 0) {
        const double cx = x + bar_w * 0.46, ya = a.px(v - errors[g], f.y1, f.y0),
                     yb = a.px(v + errors[g], f.y1, f.y0);
        o << "<path d=\"M" << num(cx) << " " << num(ya) << "V" << num(yb) << "M" << num(cx - 4)
          << " " << num(ya) << "h8M" << num(cx - 4) << " " << num(yb)
          << "h8\" stroke=\"#222222\" fill=\"none\"/>\n";
      }
    }
  }
  o << "</svg>\n";
  return o.str();
}

std::string svg_line_chart(const LineChart& c) {
  const Frame f = checked_frame(c.width, c.height, c.series);
  double xlo = INFINITY, xhi = -INFINITY, ylo = 0, yhi = 0;
  bool whole_x = true;  // e.g. epochs: ticks at whole numbers only
  for (const auto& s : c.series) {
    if (s.x.size() != s.y.size())
      throw Error("chart '" + c.title + "': series '" + s.name + "' has " +
                  std::to_string(s.x.size()) + " x and " + std::to_string(s.y.size()) +
                  " y values");
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]), xhi = std::max(xhi, s.x[i]);
      whole_x = whole_x && s.x[i] == std::round(s.x[i]);
      ylo = std::min(ylo, s.y[i]), yhi = std::max(yhi, s.y[i]);
    }
  }
  if (!std::isfinite(xlo)) xlo = 0, xhi = 1;
  if (!(xhi > xlo)) xlo -= 0.5, xhi += 0.5;  // one point: centred
  const Axis ya = make_axis(ylo, yhi, true);
  Axis xa;
  xa.lo = xlo, xa.hi = xhi, xa.step = nice_step((xhi - xlo) / 8);
  if (whole_x) xa.step = std::max(1.0, std::floor(xa.step));
  std::ostringstream o = open_chart(f, c.title, c.series, /*lines=*/true, ya, c.y_label);
  for (double v = std::ceil(xlo / xa.step - 1e-9) * xa.step; v <= xhi + xa.step * 1e-6;
       v += xa.step) {
    const double x = xa.px(v, f.x0, f.x1);
    o << "<line x1=\"" << num(x) << "\" y1=\"" << f.y1 << "\" x2=\"" << num(x) << "\" y2=\""
      << f.y1 + 4 << "\" stroke=\"" << kAxisInk << "\"/>\n<text x=\"" << num(x) << "\" y=\""
      << f.y1 + 16 << "\" text-anchor=\"middle\" fill=\"" << kAxisInk << "\">"
      << tick_text(v, xa.step) << "</text>\n";
  }
  o << "<text x=\"" << num((f.x0 + f.x1) / 2) << "\" y=\"" << c.height - 6
    << "\" text-anchor=\"middle\" fill=\"" << kAxisInk << "\">" << html_escape(c.x_label)
    << "</text>\n";
  for (std::size_t s = 0; s < c.series.size(); ++s) {
    const auto& ser = c.series[s];
    const std::string colour = chart_colour(int(s));
    std::string path;
    bool pen_down = false;
    for (std::size_t i = 0; i < ser.x.size(); ++i) {
      if (!std::isfinite(ser.x[i]) || !std::isfinite(ser.y[i])) {
        pen_down = false;
        continue;
      }
      path += (pen_down ? "L" : "M") + num(xa.px(ser.x[i], f.x0, f.x1)) + " " +
              num(ya.px(ser.y[i], f.y1, f.y0));
      pen_down = true;
    }
    if (!path.empty())
      o << "<path d=\"" << path << "\" stroke=\"" << colour
        << "\" stroke-width=\"2\" fill=\"none\"/>\n";
    for (std::size_t i = 0; c.points && i < ser.x.size(); ++i)
      if (std::isfinite(ser.x[i]) && std::isfinite(ser.y[i]))
        o << "<circle cx=\"" << num(xa.px(ser.x[i], f.x0, f.x1)) << "\" cy=\""
          << num(ya.px(ser.y[i], f.y1, f.y0)) << "\" r=\"3\" fill=\"" << colour << "\"><title>"
          << html_escape(ser.name + " at " + value_text(ser.x[i]) + ": " + value_text(ser.y[i]))
          << "</title></circle>\n";
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace ptnet
