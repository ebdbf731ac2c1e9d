// OpenSim storage files (.mot / .sto) of force plates: a header ending in
// "endheader", a line of column names, then one row of numbers per sample
// (tab- or space-separated).
#include <algorithm>
#include <cmath>
#include <map>

#include "plates/plates_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/plates.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

Table parse_storage(std::string_view text, const std::string& source) {
  Table t;
  long n = 0;
  bool header = true;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view line = text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++n;
    if (header) {
      if (trim(line) == "endheader") header = false;
      continue;
    }
    const std::vector<std::string> f = split_blanks(line);
    if (f.empty()) continue;
    if (t.columns.empty()) {
      t.columns = f;
      continue;
    }
    if (f.size() != t.columns.size())
      throw Error::at(source, n, std::to_string(t.columns.size()) + " values (one per column)", std::to_string(f.size()));
    std::vector<double> row(f.size());
    for (std::size_t c = 0; c < f.size(); ++c)
      if (!parse_number(f[c], row[c])) throw Error::at(source, n, "a number in column " + t.columns[c], escaped(f[c]));
    t.rows.push_back(std::move(row));
  }
  if (header) throw Error::in(source, "expected an OpenSim storage header ending in 'endheader', found none");
  if (t.columns.empty() || t.rows.empty()) throw Error::in(source, "no column names or no rows after 'endheader'");
  return t;
}

}  // namespace

ForcePlates parse_grf_mot(std::string_view text, const std::string& source) {
  const Table t = parse_storage(text, source);
  const int time = int(std::find(t.columns.begin(), t.columns.end(), "time") - t.columns.begin());
  if (time == int(t.columns.size())) throw Error::in(source, "no 'time' column");
  std::map<std::string, int> index;
  for (std::size_t c = 0; c < t.columns.size(); ++c) index[t.columns[c]] = int(c);
  ForcePlates p;
  p.source = source;
  for (const auto& row : t.rows) {
    if (!p.time_s.empty() && !(row[std::size_t(time)] > p.time_s.back()))
      throw Error::in(source, "expected increasing times, found " + number_text(row[std::size_t(time)]) +
                                  " after " + number_text(p.time_s.back()));
    p.time_s.push_back(row[std::size_t(time)]);
  }
  for (const std::string& name : t.columns) {
    if (!ends_with(name, "vx") || name.find("force") == std::string::npos) continue;
    const std::string prefix = name.substr(0, name.size() - 2);
    std::array<int, 6> c{};
    bool all = true;
    int k = 0;
    for (const char* s : {"vx", "vy", "vz", "px", "py", "pz"}) {
      auto it = index.find(prefix + s);
      all = all && it != index.end();
      c[std::size_t(k++)] = all ? it->second : -1;
    }
    if (!all) continue;
    ForcePlates::Plate plate;
    plate.prefix = prefix;
    for (const auto& row : t.rows) {
      plate.force_n.emplace_back(row[std::size_t(c[0])], row[std::size_t(c[1])], row[std::size_t(c[2])]);
      plate.cop_m.emplace_back(row[std::size_t(c[3])], row[std::size_t(c[4])], row[std::size_t(c[5])]);
    }
    p.plates.push_back(std::move(plate));
  }
  if (p.plates.empty())
    throw Error::in(source, "no force plate columns (expected PREFIX vx vy vz px py pz, e.g. ground_force_vx); found " +
                                join(t.columns, " "));
  return p;
}

ForcePlates read_grf_mot(const std::string& path) {
  note_input(path);
  return parse_grf_mot(read_text_file(path), path);
}

}  // namespace ptnet
