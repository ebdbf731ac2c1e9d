// What a dataset's mat reads as a force plate would, per sequence and frame,
// as OpenSim storage or CSV files (ptnet/data.hpp: write_mat_forces).
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "core/anthropometry.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

std::vector<std::string> write_mat_forces(const Dataset& dataset, const std::vector<std::string>& names,
                                          const std::string& dir, TableFormat format, bool force,
                                          double contact_kpa) {
  check_range("contact_kpa", contact_kpa, kPressureRangeKpa);
  std::vector<std::string> chosen = names;
  if (chosen.empty())
    for (const auto& s : dataset.sequences()) chosen.push_back(s.name);
  std::vector<std::string> files;
  for (const auto& name : chosen) {
    dataset.sequence(name);  // an Error naming the dataset if absent
    if (const std::string problem = name_problem(name); !problem.empty())
      throw Error("sequence " + escaped(name) + " " + problem + ": it cannot name a file");
    files.push_back(name + "." + table_format_name(format));
  }
  if (!first_repeat(files).empty()) throw Error("sequences: " + escaped(first_repeat(files)) + " given twice");
  check_outputs_in_folder(dir, files, force);
  make_folder(dir);
  const MatSpec& mat = dataset.info().mat;
  std::vector<std::string> written;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const SequenceMeta& meta = dataset.sequence(chosen[k]);
    const double mass = dataset.body(meta.body_id).weight_kg;
    const double bw = mass * anthropometry::kGravity;
    const PressureSequence seq = dataset.read(meta.name);
    std::vector<std::vector<double>> rows;
    rows.reserve(std::size_t(seq.frames()));
    for (int t = 0; t < seq.frames(); ++t) {
      const FrameLoad f = frame_load(seq.frame(t), mat, contact_kpa);
      rows.push_back({t / seq.fps, f.force_n, f.force_n / bw, f.x_m, f.y_m, f.contact_m2 * 1e4});
    }
    std::ostringstream note;
    note << std::setprecision(9) << "units: N for ground_force_vy, body weights for ground_force_bw (body "
         << meta.body_id << ", " << mass << " kg); mat_cop_x, mat_cop_y in m from the mat's centre (x towards row 0, "
         << "y towards column 0; nan: nothing loaded); contact cells above " << contact_kpa << " kPa";
    const std::string path = (std::filesystem::path(dir) / files[k]).string();
    write_table_file(path, {"time", "ground_force_vy", "ground_force_bw", "mat_cop_x", "mat_cop_y", "contact_area_cm2"},
                     rows, note.str(), force);
    written.push_back(path);
  }
  return written;
}

}  // namespace ptnet
