// OpenSim marker files (.trc): a header of three lines (PathFileType; the
// names and values of DataRate, NumFrames, NumMarkers, Units, ...), the
// marker names (each spans its X, Y, Z columns), the X1 Y1 Z1 labels, then
// one row per frame: Frame#, Time, X Y Z per marker; a blank cell (or "nan")
// is a missing sample. Read as OpenSim's TRCFileAdapter reads them, and then
// some: the header's words between any blanks (spaces, padding, doubled
// tabs), a line with tabs split on tabs and one without on runs of spaces,
// blank lines anywhere, LF or CRLF, a UTF-8 byte-order mark (LineReader).
// The rows are reserved from the text's line count (never from the header's
// counts) and the Time column must agree with DataRate.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

#include "motion/markers_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

using detail::kNaN;
constexpr int kMaxMarkers = 10000;
constexpr double kMaxRateHz = 100000;
// The Time column's rate may differ from DataRate by this fraction (times
// written with few decimals) before the file is refused.
constexpr double kRateTolerance = 0.02;

using Cells = std::vector<std::string_view>;

// The cells of a line: between tabs, each trimmed (a blank cell is a missing
// value); a line without tabs: its words.
void cells(std::string_view line, Cells& out) {
  if (line.find('\t') == std::string_view::npos) return split_blanks(line, out);
  split_views(line, '\t', out);
}

bool equals_nocase(std::string_view a, std::string_view b) {
  const auto low = [](char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; };
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [&](char x, char y) { return low(x) == low(y); });
}

// A number cell: the fast path (std::from_chars) and, for what it refuses
// ("+1", ".5e"), parse_number.
bool number(std::string_view s, double& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec == std::errc() && r.ptr == s.data() + s.size()) return std::isfinite(v);
  return parse_number(s, v);
}

double metres_per_trc_unit(std::string_view units, const std::string& source, long line) {
  const std::string u = lower(std::string(units));
  if (u == "mm" || u == "millimeters" || u == "millimetres") return 0.001;
  if (u == "cm" || u == "centimeters" || u == "centimetres") return 0.01;
  if (u == "m" || u == "meters" || u == "metres") return 1.0;
  throw Error::at(source, line, "Units mm, cm or m", units.empty() ? "none" : escaped(units));
}

struct Header {
  double rate = 0, scale = 0.001;
  long frames = -1, markers = -1;
  long values_line = 3;  // the line of the values, for messages
};

// The header's names and values, paired: in order when the two lines have as
// many words (padding and doubled tabs between them are no values), else by
// tab column (a blank value under its name).
std::vector<std::pair<std::string_view, std::string_view>> header_pairs(std::string_view names_line,
                                                                       std::string_view values_line,
                                                                       const std::string& source, long n) {
  Cells names, values;
  split_blanks(names_line, names);
  split_blanks(values_line, values);
  if (names.size() != values.size()) {
    if (names_line.find('\t') == std::string_view::npos || values_line.find('\t') == std::string_view::npos)
      throw Error::at(source, n, std::to_string(names.size()) + " values, one per name of line " + std::to_string(n - 1),
                      std::to_string(values.size()));
    cells(names_line, names);
    cells(values_line, values);
  }
  std::vector<std::pair<std::string_view, std::string_view>> out;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (!names[i].empty()) out.emplace_back(names[i], i < values.size() ? values[i] : std::string_view());
  return out;
}

void header_value(Header& h, std::string_view name, std::string_view v, const std::string& source, long n) {
  double x = 0;
  const std::string found = v.empty() ? std::string("none") : escaped(v);
  if (equals_nocase(name, "DataRate")) {
    if (!parse_number(v, x) || !(x > 0) || !(x <= kMaxRateHz))
      throw Error::at(source, n, "a DataRate in (0, " + number_text(kMaxRateHz) + "] Hz", found);
    h.rate = x;
  } else if (equals_nocase(name, "NumFrames") || equals_nocase(name, "NumMarkers")) {
    if (!parse_number(v, x) || x < 0 || x != std::trunc(x) || x > 1e8)
      throw Error::at(source, n, "a whole " + std::string(name), found);
    (equals_nocase(name, "NumFrames") ? h.frames : h.markers) = long(x);
  } else if (equals_nocase(name, "Units")) {
    h.scale = metres_per_trc_unit(v, source, n);
  }
}

Header parse_header(LineReader& lines, const std::string& source) {
  std::string_view line;
  Cells first;
  const bool any = lines.next(line);
  if (any) split_blanks(line, first);
  if (first.empty() || !equals_nocase(first[0], "PathFileType"))
    throw Error::at(source, 1, "PathFileType (an OpenSim .trc file)",
                    trim_view(line).empty() ? std::string("an empty line") : escaped(line.substr(0, 40)));
  std::string_view names_line, values_line;
  if (!lines.next(names_line) || !lines.next(values_line))
    throw Error::at(source, lines.number() + 1, "the header's names and values", "end of file");
  Header h;
  h.values_line = lines.number();
  for (const auto& [name, value] : header_pairs(names_line, values_line, source, h.values_line))
    header_value(h, name, value, source, h.values_line);
  if (!(h.rate > 0)) throw Error::at(source, h.values_line - 1, "DataRate among the header's names", "none");
  return h;
}

std::vector<std::string> parse_marker_names(std::string_view line, const std::string& source, long n) {
  Cells c;
  cells(line, c);
  c.erase(std::remove(c.begin(), c.end(), std::string_view()), c.end());  // the Y and Z columns of each marker
  if (c.size() < 2 || !equals_nocase(c[0], "Frame#") || !equals_nocase(c[1], "Time"))
    throw Error::at(source, n, "Frame# and Time then the marker names", c.empty() ? "an empty line" : escaped(line.substr(0, 40)));
  std::vector<std::string> names;
  std::unordered_set<std::string_view> seen;
  for (std::size_t i = 2; i < c.size(); ++i) {
    if (!seen.insert(c[i]).second) throw Error::at(source, n, "distinct marker names", escaped(c[i]) + " twice");
    names.emplace_back(c[i]);
  }
  if (names.empty()) throw Error::at(source, n, "at least one marker name", "none");
  if (int(names.size()) > kMaxMarkers)
    throw Error::at(source, n, "at most " + std::to_string(kMaxMarkers) + " markers", std::to_string(names.size()));
  return names;
}

// The X1 Y1 Z1 labels line (its first word X1, any case).
bool is_axis_labels(const Cells& c) {
  for (std::string_view s : c)
    if (!s.empty()) return s.size() >= 2 && (s[0] == 'X' || s[0] == 'x') && s[1] >= '0' && s[1] <= '9';
  return false;
}

// One row's cells, checked against the row width (Frame#, Time, 3 per
// marker): blank cells past the last marker's Z are padding; a row with more
// cells whose non-blank ones are exactly the width was padded with doubled
// tabs; fewer cells are missing markers at the end of the row.
std::size_t row_cells(Cells& c, std::size_t width, const std::string& source, long n, std::size_t markers) {
  std::size_t used = c.size();
  while (used > width && c[used - 1].empty()) --used;
  if (used > width) {
    const auto filled = std::size_t(std::count_if(c.begin(), c.end(), [](std::string_view s) { return !s.empty(); }));
    if (filled == width) {
      c.erase(std::remove(c.begin(), c.end(), std::string_view()), c.end());
      used = width;
    }
  }
  if (used > width || used < 2)
    throw Error::at(source, n,
                    "at most " + std::to_string(width) + " values (Frame#, Time, " + std::to_string(markers) +
                        " markers x 3)",
                    std::to_string(used));
  return used;
}

void parse_row(Cells& c, Trc& trc, const std::string& source, long n) {
  const std::size_t M = trc.markers.size();
  const std::size_t used = row_cells(c, 2 + 3 * M, source, n, M);
  double t = 0;
  if (!number(c[1], t))
    throw Error::at(source, n, "a time in seconds", c[1].empty() ? "a blank cell" : escaped(c[1]));
  if (!trc.time_s.empty() && !(t > trc.time_s.back()))
    throw Error::at(source, n, "a time after " + number_text(trc.time_s.back()) + " s", escaped(c[1]));
  trc.time_s.push_back(t);
  for (std::size_t m = 0; m < M; ++m) {
    Eigen::Vector3d p(kNaN, kNaN, kNaN);
    int blanks = 0;
    for (int a = 0; a < 3; ++a) {
      const std::size_t k = 2 + 3 * m + std::size_t(a);
      const std::string_view s = k < used ? c[k] : std::string_view();
      if (s.empty() || equals_nocase(s, "nan")) {
        ++blanks;
        continue;
      }
      double v = 0;
      if (!number(s, v) || std::abs(v) > 1e9)
        throw Error::at(source, n, "a coordinate of " + escaped(trc.markers[m]), escaped(s));
      p[a] = v;
    }
    if (blanks > 0 && blanks < 3)
      throw Error::at(source, n, "all three or none of " + escaped(trc.markers[m]) + "'s X Y Z",
                      std::to_string(3 - blanks) + " of them");
    trc.xyz.push_back(blanks ? Eigen::Vector3d(kNaN, kNaN, kNaN) : p);
  }
}

// The Time column against DataRate: the mean step over the trial (times
// rounded to few decimals) or the median step (a few rows left out) must be
// within kRateTolerance of 1 / DataRate.
void check_rate(const Trc& trc, const std::string& source, long line) {
  const std::size_t F = trc.time_s.size();
  if (F < 2) return;
  const double mean_step = (trc.time_s.back() - trc.time_s.front()) / double(F - 1);
  std::vector<double> steps(F - 1);
  for (std::size_t f = 1; f < F; ++f) steps[f - 1] = trc.time_s[f] - trc.time_s[f - 1];
  std::nth_element(steps.begin(), steps.begin() + std::ptrdiff_t(steps.size() / 2), steps.end());
  const double median_step = steps[steps.size() / 2];
  auto agrees = [&](double step) { return std::abs(step * trc.rate_hz - 1) <= kRateTolerance; };
  if (agrees(mean_step) || agrees(median_step)) return;
  const double time_rate = 1 / mean_step;
  const bool swapped = std::abs(trc.rate_hz * time_rate - 1) <= kRateTolerance;
  throw Error::at(source, line,
                  "a DataRate the Time column agrees with (its steps are " + number_text(mean_step) + " s: " +
                      number_text(time_rate) + " Hz)",
                  number_text(trc.rate_hz) + (swapped ? " (the frame time written as the rate?)" : ""));
}

// Rows of at most `rows` frames of M markers: reserved once (what the text
// can hold, checked against the available memory).
void reserve_rows(Trc& trc, std::size_t rows, const std::string& source) {
  const std::uint64_t samples = checked_mul(rows, trc.markers.size(), source, "the marker samples");
  check_memory(checked_mul(samples, sizeof(Eigen::Vector3d), source, "the marker samples' bytes"), source,
               "the marker samples");
  trc.time_s.reserve(rows);
  trc.xyz.reserve(std::size_t(samples));
}

}  // namespace

int Trc::find(std::string_view name) const {
  for (std::size_t i = 0; i < markers.size(); ++i)
    if (markers[i] == name) return int(i);
  return -1;
}

bool is_trc_path(const std::string& path) {
  return path.size() >= 4 && lower(path.substr(path.size() - 4)) == ".trc";
}

Trc parse_trc(std::string_view text, const std::string& source) {
  LineReader lines(text);
  const Header h = parse_header(lines, source);
  Trc trc;
  trc.source = source;
  trc.rate_hz = h.rate;
  trc.metres_per_unit = h.scale;
  std::string_view line;
  if (!lines.next(line)) throw Error::at(source, lines.number() + 1, "the marker names", "end of file");
  trc.markers = parse_marker_names(line, source, lines.number());
  const std::size_t M = trc.markers.size();
  if (h.markers >= 0 && std::size_t(h.markers) != M)
    throw Error::at(source, lines.number(), std::to_string(h.markers) + " marker names (NumMarkers)",
                    std::to_string(M));
  reserve_rows(trc, lines.lines_left(), source);
  Cells c;
  for (bool first = true; lines.next(line);) {
    cells(line, c);
    if (std::all_of(c.begin(), c.end(), [](std::string_view s) { return s.empty(); })) continue;
    if (std::exchange(first, false) && is_axis_labels(c)) continue;
    parse_row(c, trc, source, lines.number());
  }
  if (trc.time_s.empty()) throw Error::in(source, "expected rows of Frame#, Time, X Y Z ..., found none");
  if (h.frames >= 0 && h.frames != long(trc.time_s.size()))
    throw Error::in(source, "expected " + std::to_string(h.frames) + " frames (NumFrames), found " +
                                std::to_string(trc.time_s.size()) + " (a truncated file?)");
  check_rate(trc, source, h.values_line);
  return trc;
}

Trc read_trc(const std::string& path) {
  note_input(path);
  const std::string text = read_text_file(path);
  if (text.empty()) throw Error::at(path, 1, "PathFileType (an OpenSim .trc file)", "an empty file");
  return parse_trc(text, path);
}

}  // namespace ptnet
