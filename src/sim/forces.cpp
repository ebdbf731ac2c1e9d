// The simulated ground reaction of a sequence, frame by frame, and its
// file: an OpenSim storage file (.mot) or CSV.
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/anthropometry.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/sim.hpp"

namespace ptnet {

void write_force_table(const ForceTable& f, const std::string& path, bool force) {
  const std::size_t T = f.time_s.size();
  if (f.total_n.size() != T || f.foot_n.size() != T || f.cop_u.size() != T || f.carried_n.size() != T ||
      (!f.cop_m.empty() && f.cop_m.size() != T))
    throw Error::in(path, "a force table's columns must have one value per time (" + std::to_string(T) +
                              "); found total " + std::to_string(f.total_n.size()) + ", feet " +
                              std::to_string(f.foot_n.size()) + ", cop " + std::to_string(f.cop_u.size()) +
                              ", carried " + std::to_string(f.carried_n.size()) + ", cop_m " +
                              std::to_string(f.cop_m.size()));
  if (!(f.mass_kg > 0)) throw Error::in(path, "a force table's mass must be positive, found " + std::to_string(f.mass_kg));
  const double bw = f.mass_kg * anthropometry::kGravity;
  std::vector<std::vector<double>> rows;
  rows.reserve(f.time_s.size());
  for (std::size_t t = 0; t < f.time_s.size(); ++t) {
    rows.push_back({f.time_s[t], f.total_n[t], f.total_n[t] / bw, f.foot_n[t][0], f.foot_n[t][1],
                    f.foot_n[t][0] / bw, f.foot_n[t][1] / bw, f.cop_u[t][0], f.cop_u[t][1], f.carried_n[t] / bw});
    for (std::size_t s = 0; s < 2; ++s) {  // vx, vz, px, py, pz: OpenSim's axes (y up)
      const Eigen::Vector2d p = f.cop_m.empty() ? Eigen::Vector2d::Zero() : f.cop_m[t][s];
      rows.back().insert(rows.back().end(), {0.0, 0.0, p.y(), 0.0, p.x()});
    }
  }
  std::vector<std::string> columns{"time",       "total_force_vy", "total_force_bw", "l_ground_force_vy",
                                   "r_ground_force_vy", "l_force_bw", "r_force_bw", "l_cop_u", "r_cop_u", "carried_bw"};
  for (const char* foot : {"l_ground_force_", "r_ground_force_"})
    for (const char* c : {"vx", "vz", "px", "py", "pz"}) columns.push_back(std::string(foot) + c);
  std::ostringstream note;
  note << std::setprecision(9) << "units: N for *_vy, body weights for *_bw (mass " << f.mass_kg
       << " kg), cop_u 0 heel .. 1 toe along the foot (nan: unloaded), carried_bw the load a seat carries off the "
          "floor; l_/r_ground_force_v* N and p* m in OpenSim's axes, y up (px, pz: the motion's world y, x; 0: unloaded)";
  write_table_file(path, columns, rows, note.str(), force);
}

ForceTable force_table(const std::vector<FrameTrace>& trace, const Motion& motion, const Body& body) {
  ForceTable f;
  f.mass_kg = body.mass_kg();
  for (std::size_t t = 0; t < trace.size(); ++t) {
    f.time_s.push_back(motion.start_s + double(t) / motion.fps);
    f.total_n.push_back(trace[t].load_n);
    f.carried_n.push_back(trace[t].carried_n);
    std::array<double, 2> n{}, u{};
    std::array<Eigen::Vector2d, 2> at{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
    for (int s = 0; s < 2; ++s) {
      n[std::size_t(s)] = trace[t].foot[std::size_t(s)].force_n;
      u[std::size_t(s)] = trace[t].foot[std::size_t(s)].cop_u >= 0 ? trace[t].foot[std::size_t(s)].cop_u : NAN;
      if (std::isfinite(u[std::size_t(s)]) && t < motion.frames.size()) {
        const auto ends = foot_ends(motion.frames[t], s);  // heel back, toe tip
        at[std::size_t(s)] = (ends[0] + u[std::size_t(s)] * (ends[1] - ends[0])).head<2>();
      }
    }
    f.foot_n.push_back(n);
    f.cop_u.push_back(u);
    f.cop_m.push_back(at);
  }
  return f;
}

}  // namespace ptnet
