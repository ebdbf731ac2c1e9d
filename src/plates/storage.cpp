// Force plates from a numeric table (OpenSim storage .mot / .sto, or CSV:
// ptnet/io.hpp's TableReader): each group of columns PREFIX + vx vy vz px
// py pz is a plate. Only those columns and the time are parsed, row by row:
// the memory is the file's text and what is kept, 8 + 48 bytes per plate
// per sample, reserved once from the rows left and checked against the
// memory available first, however wide the file.
#include <algorithm>
#include <cmath>

#include "plates/plates_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/plates.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

constexpr const char* kPlateColumns[6] = {"vx", "vy", "vz", "px", "py", "pz"};

// The plates' columns: every PREFIX + vx whose prefix holds "force" and
// whose five companions are there. Indices into t.columns(), six a plate.
std::vector<std::pair<std::string, std::array<int, 6>>> plate_groups(const TableReader& t) {
  std::vector<std::pair<std::string, std::array<int, 6>>> out;
  for (const std::string& name : t.columns()) {
    if (!ends_with(name, "vx") || name.find("force") == std::string::npos) continue;
    const std::string prefix = name.substr(0, name.size() - 2);
    std::array<int, 6> c{};
    bool all = true;
    for (std::size_t k = 0; k < 6; ++k) all = all && (c[k] = t.column(prefix + kPlateColumns[k])) >= 0;
    if (all) out.emplace_back(prefix, c);
  }
  return out;
}

// Room for `rows` samples in every array, checked against the memory
// available first.
void reserve_samples(ForcePlates& p, std::size_t rows, const std::string& source) {
  const std::uint64_t per_sample = sizeof(double) + p.plates.size() * 2 * sizeof(Eigen::Vector3d);
  check_memory(checked_mul(rows, per_sample, source, "the plate samples"), source, "the plate samples");
  p.time_s.reserve(rows);
  for (auto& plate : p.plates) {
    plate.force_n.reserve(rows);
    plate.cop_m.reserve(rows);
  }
}

ForcePlates read_plates(TableReader& t) {
  const std::string& source = t.source();
  const int time = t.column("time");
  if (time < 0) throw Error::in(source, "no 'time' column");
  const auto groups = plate_groups(t);
  if (groups.empty())
    throw Error::in(source, "no force plate columns (expected PREFIX vx vy vz px py pz, e.g. ground_force_vx); found " +
                                escaped(join(t.columns(), " "), 400, false));
  std::vector<int> use{time};
  ForcePlates p;
  p.source = source;
  for (const auto& [prefix, c] : groups) {
    use.insert(use.end(), c.begin(), c.end());
    p.plates.push_back({prefix, {}, {}, {}});
  }
  reserve_samples(p, t.rows_left(), source);
  for (std::vector<double> v; t.next(use, v);) {
    if (!p.time_s.empty() && !(v[0] > p.time_s.back()))
      throw Error::in(source, "expected increasing times, found " + number_text(v[0]) + " after " +
                                  number_text(p.time_s.back()));
    p.time_s.push_back(v[0]);
    for (std::size_t k = 0; k < p.plates.size(); ++k) {
      const double* x = &v[1 + 6 * k];
      p.plates[k].force_n.emplace_back(x[0], x[1], x[2]);
      p.plates[k].cop_m.emplace_back(x[3], x[4], x[5]);
    }
  }
  if (p.time_s.empty()) throw Error::in(source, "no rows after the column names");
  return p;
}

}  // namespace

ForcePlates parse_grf_mot(std::string_view text, const std::string& source) {
  TableReader t(text, source, TableFormat::mot);
  return read_plates(t);
}

ForcePlates read_grf_mot(const std::string& path) {
  note_input(path);
  TableReader t(path);
  return read_plates(t);
}

}  // namespace ptnet
