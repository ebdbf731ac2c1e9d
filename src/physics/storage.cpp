// OpenSim storage files (.mot / .sto): the force plates read, the simulator's
// forces written. A storage file is a header ending in "endheader", a line
// of column names, then one row of numbers per sample (tab- or
// space-separated).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "ptnet/anthropometry.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/physics.hpp"
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

void write_force_table(const ForceTable& f, const std::string& path, bool force) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext != ".mot" && ext != ".sto" && ext != ".csv")
    throw Error::in(path, "expected a .mot, .sto or .csv file name");
  const bool csv = ext == ".csv";
  const double bw = f.mass_kg * anthropometry::kGravity;
  const std::vector<std::string> columns = {"time",         "total_force_vy", "total_force_bw", "l_ground_force_vy",
                                            "r_ground_force_vy", "l_force_bw",  "r_force_bw",     "l_cop_u",
                                            "r_cop_u"};
  std::ostringstream o;
  o << std::setprecision(9);
  const char sep = csv ? ',' : '\t';
  if (!csv)
    o << std::filesystem::path(path).stem().string() << "\nversion=1\nnRows=" << f.time_s.size()
      << "\nnColumns=" << columns.size() << "\ninDegrees=no\n"
      << "units: N for *_vy, body weights for *_bw (mass " << f.mass_kg
      << " kg), cop_u 0 heel .. 1 toe along the foot (nan: unloaded)\nendheader\n";
  o << join(columns, std::string(1, sep)) << "\n";
  for (std::size_t t = 0; t < f.time_s.size(); ++t) {
    o << f.time_s[t] << sep << f.total_n[t] << sep << f.total_n[t] / bw;
    for (int s = 0; s < 2; ++s) o << sep << f.foot_n[t][std::size_t(s)];
    for (int s = 0; s < 2; ++s) o << sep << f.foot_n[t][std::size_t(s)] / bw;
    for (int s = 0; s < 2; ++s) o << sep << f.cop_u[t][std::size_t(s)];
    o << "\n";
  }
  write_text_file(path, o.str(), force);
}

ForceTable force_table(const std::vector<FrameTrace>& trace, const Motion& motion, const Body& body) {
  ForceTable f;
  f.mass_kg = body.mass_kg();
  for (std::size_t t = 0; t < trace.size(); ++t) {
    f.time_s.push_back(motion.start_s + double(t) / motion.fps);
    f.total_n.push_back(trace[t].load_n);
    std::array<double, 2> n{}, u{};
    for (int s = 0; s < 2; ++s) {
      n[std::size_t(s)] = trace[t].foot[std::size_t(s)].force_n;
      u[std::size_t(s)] = trace[t].foot[std::size_t(s)].cop_u >= 0 ? trace[t].foot[std::size_t(s)].cop_u : NAN;
    }
    f.foot_n.push_back(n);
    f.cop_u.push_back(u);
  }
  return f;
}

}  // namespace ptnet
