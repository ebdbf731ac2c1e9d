// The simulated ground reaction of a sequence, frame by frame, and its
// file: an OpenSim storage file (.mot) or CSV.
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "core/anthropometry.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

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
