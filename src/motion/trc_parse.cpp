// OpenSim marker files (.trc): a header of three lines (PathFileType; the
// names and values of DataRate, NumFrames, NumMarkers, Units, ...), the
// marker names (each spans its X, Y, Z columns), the X1 Y1 Z1 labels, then
// one row per frame: Frame#, Time, X Y Z per marker; a blank cell is a
// missing sample. Tab-separated; a file without tabs is split on spaces
// (then no cell can be blank). LF or CRLF, a UTF-8 byte-order mark.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "motion/markers_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxMarkers = 10000;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\r' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The cells of a line: split on tabs, each trimmed; on runs of spaces when
// the file has no tabs.
std::vector<std::string_view> cells(std::string_view line, bool tabs) {
  std::vector<std::string_view> out;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (tabs) {
    std::size_t start = 0;
    for (;;) {
      const std::size_t tab = line.find('\t', start);
      out.push_back(trim(line.substr(start, tab == std::string_view::npos ? std::string_view::npos : tab - start)));
      if (tab == std::string_view::npos) break;
      start = tab + 1;
    }
  } else {
    std::size_t i = 0;  // views into `line`, as split_blanks splits
    while (i < line.size()) {
      while (i < line.size() && line[i] == ' ') ++i;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ') ++i;
      if (i > start) out.push_back(line.substr(start, i - start));
    }
  }
  return out;
}

class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
  }
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t nl = text_.find('\n', pos_);
    line = text_.substr(pos_, nl == std::string_view::npos ? std::string_view::npos : nl - pos_);
    pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
    ++number_;
    return true;
  }
  long number() const { return number_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  long number_ = 0;
};

double metres_per_trc_unit(std::string_view units, const std::string& source, long line) {
  const std::string u = lower(std::string(units));
  if (u == "mm") return 0.001;
  if (u == "cm") return 0.01;
  if (u == "m") return 1.0;
  throw Error::at(source, line, "Units mm, cm or m", units.empty() ? "none" : escaped(units));
}

struct Header {
  double rate = 0, scale = 0.001;
  long frames = -1, markers = -1;
};

Header parse_header(Lines& lines, bool tabs, const std::string& source) {
  std::string_view line;
  if (!lines.next(line) || cells(line, tabs).empty() || cells(line, tabs)[0] != "PathFileType")
    throw Error::at(source, 1, "PathFileType (an OpenSim .trc file)",
                    line.empty() ? std::string("an empty line") : escaped(line.substr(0, 40)));
  std::string_view names_line, values_line;
  if (!lines.next(names_line) || !lines.next(values_line))
    throw Error::at(source, lines.number() + 1, "the header's names and values", "end of file");
  const auto names = cells(names_line, tabs), values = cells(values_line, tabs);
  Header h;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].empty()) continue;
    const std::string_view v = i < values.size() ? values[i] : std::string_view();
    double x = 0;
    if (names[i] == "DataRate") {
      if (!parse_number(v, x) || !(x > 0) || !(x <= 100000))
        throw Error::at(source, 3, "a DataRate in (0, 100000] Hz", v.empty() ? "none" : escaped(v));
      h.rate = x;
    } else if (names[i] == "NumFrames" || names[i] == "NumMarkers") {
      if (!parse_number(v, x) || x < 0 || x != std::trunc(x) || x > 1e8)
        throw Error::at(source, 3, "a whole " + std::string(names[i]), v.empty() ? "none" : escaped(v));
      (names[i] == "NumFrames" ? h.frames : h.markers) = long(x);
    } else if (names[i] == "Units") {
      h.scale = metres_per_trc_unit(v, source, 3);
    }
  }
  if (!(h.rate > 0)) throw Error::at(source, 2, "DataRate among the header's names", "none");
  return h;
}

std::vector<std::string> parse_marker_names(std::string_view line, bool tabs, const std::string& source, long n) {
  const auto c = cells(line, tabs);
  if (c.size() < 2 || c[0] != "Frame#" || c[1] != "Time")
    throw Error::at(source, n, "Frame# and Time then the marker names", c.empty() ? "an empty line" : escaped(line.substr(0, 40)));
  std::vector<std::string> names;
  std::unordered_set<std::string> seen;
  for (std::size_t i = 2; i < c.size(); ++i) {
    if (c[i].empty()) continue;  // the Y and Z columns of the previous marker
    std::string name(c[i]);
    if (!seen.insert(name).second) throw Error::at(source, n, "distinct marker names", escaped(name) + " twice");
    names.push_back(std::move(name));
  }
  if (names.empty()) throw Error::at(source, n, "at least one marker name", "none");
  if (int(names.size()) > kMaxMarkers)
    throw Error::at(source, n, "at most " + std::to_string(kMaxMarkers) + " markers", std::to_string(names.size()));
  return names;
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
  const bool tabs = text.find('\t') != std::string_view::npos;
  Lines lines(text);
  const Header h = parse_header(lines, tabs, source);
  Trc trc;
  trc.source = source;
  trc.rate_hz = h.rate;
  trc.metres_per_unit = h.scale;
  std::string_view line;
  if (!lines.next(line)) throw Error::at(source, lines.number() + 1, "the marker names", "end of file");
  trc.markers = parse_marker_names(line, tabs, source, lines.number());
  const std::size_t M = trc.markers.size();
  if (h.markers >= 0 && std::size_t(h.markers) != M)
    throw Error::at(source, lines.number(), std::to_string(h.markers) + " marker names (NumMarkers)",
                    std::to_string(M));
  const std::size_t width = 2 + 3 * M;
  while (lines.next(line)) {
    const auto c = cells(line, tabs);
    const bool blank = std::all_of(c.begin(), c.end(), [](std::string_view s) { return s.empty(); });
    if (blank) continue;
    if (trc.time_s.empty() && c.size() > 2 && !c[2].empty() && (c[2][0] == 'X' || c[2][0] == 'x'))
      continue;  // the X1 Y1 Z1 labels
    // Cells past the last marker's Z are blank padding; fewer cells are
    // missing markers at the end of the row.
    std::size_t used = c.size();
    while (used > width && c[used - 1].empty()) --used;
    if (used > width || used < 2)
      throw Error::at(source, lines.number(),
                      "at most " + std::to_string(width) + " values (Frame#, Time, " + std::to_string(M) +
                          " markers x 3)",
                      std::to_string(used));
    double t = 0;
    if (!parse_number(c[1], t) || !std::isfinite(t))
      throw Error::at(source, lines.number(), "a time in seconds", c[1].empty() ? "a blank cell" : escaped(c[1]));
    if (!trc.time_s.empty() && !(t > trc.time_s.back()))
      throw Error::at(source, lines.number(), "a time after " + number_text(trc.time_s.back()) + " s", escaped(c[1]));
    trc.time_s.push_back(t);
    for (std::size_t m = 0; m < M; ++m) {
      Eigen::Vector3d p(kNaN, kNaN, kNaN);
      int blanks = 0;
      for (int a = 0; a < 3; ++a) {
        const std::size_t k = 2 + 3 * m + std::size_t(a);
        const std::string_view s = k < used ? c[k] : std::string_view();
        if (s.empty() || lower(std::string(s)) == "nan") {
          ++blanks;
          continue;
        }
        double v = 0;
        if (!parse_number(s, v) || !std::isfinite(v) || std::abs(v) > 1e9)
          throw Error::at(source, lines.number(), "a coordinate of " + escaped(trc.markers[m]), escaped(s));
        p[a] = v;
      }
      if (blanks > 0 && blanks < 3)
        throw Error::at(source, lines.number(), "all three or none of " + escaped(trc.markers[m]) + "'s X Y Z",
                        std::to_string(3 - blanks) + " of them");
      trc.xyz.push_back(blanks ? Eigen::Vector3d(kNaN, kNaN, kNaN) : p);
    }
  }
  if (trc.time_s.empty()) throw Error::in(source, "expected rows of Frame#, Time, X Y Z ..., found none");
  if (h.frames >= 0 && h.frames != long(trc.time_s.size()))
    throw Error::in(source, "expected " + std::to_string(h.frames) + " frames (NumFrames), found " +
                                std::to_string(trc.time_s.size()) + " (a truncated file?)");
  return trc;
}

Trc read_trc(const std::string& path) {
  note_input(path);
  const std::string text = read_text_file(path);
  if (text.empty()) throw Error::at(path, 1, "PathFileType (an OpenSim .trc file)", "an empty file");
  return parse_trc(text, path);
}

}  // namespace ptnet
