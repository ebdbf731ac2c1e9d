// ptnet info FILE: what a motion file holds.
//
//   ptnet info walk.bvh            # joints, frames, fps, units, height, mapping
//   ptnet info walk.bvh --json     # the same, machine-readable
//   ptnet info trial.c3d           # markers, frames, analog channels, force plates, the writer
//
// One describe function per file type; main dispatch in describe().
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "command.hpp"
#include "ptnet/c3d.hpp"
#include "ptnet/error.hpp"
#include "ptnet/data.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::cli::cmd_info {
namespace {

struct InfoCli {
  std::string file;
  bool json = false;
  std::string units = "auto";
  std::string up = "y";
  bool keep_tpose = false;
  std::string marker_map, static_markers;  // .trc
};

// The unit metres_per_unit() chose (auto) or was given.
Units units_of(const Bvh& bvh, Units asked, UpAxis up) {
  if (asked != Units::automatic) return asked;
  const double m = metres_per_unit(bvh, Units::automatic, up);
  for (Units u : {Units::m, Units::cm, Units::mm, Units::in, Units::cmu})
    if (metres_per_unit(bvh, u, up) == m) return u;
  return Units::automatic;
}

// What the motion lacks to carry its own dynamics (check_dynamics with the
// default simulation options), and the warnings for it (simulate checks
// with its run's options: placement and compliance can change the figures).
void add_dynamics(nlohmann::ordered_json& j, const Motion& motion) {
  const MotionDynamics d = check_dynamics(motion, SimOptions{});
  j["dynamics"] = {{"frozen_pelvis", d.frozen_pelvis}, {"unsupported", d.unsupported},
                   {"warnings", dynamics_warnings(motion.name, d)}};
}

void print_warnings(std::ostringstream& s, const nlohmann::ordered_json& j) {
  for (const auto& w : j["dynamics"]["warnings"]) s << "  warning           " << w.get<std::string>() << "\n";
}

nlohmann::ordered_json describe_bvh(const InfoCli& o) {
  const Bvh bvh = read_bvh(o.file);
  MotionOptions mo;
  mo.units = parse_units(o.units);
  mo.up = parse_up_axis(o.up);
  mo.keep_tpose = o.keep_tpose;
  const Units units = units_of(bvh, mo.units, mo.up);
  const double scale = metres_per_unit(bvh, mo.units, mo.up);
  const auto map = map_canonical(bvh);
  const bool tpose = bvh.frames() > 1 && is_tpose(bvh, 0, map, scale, mo.up);
  const Motion motion = motion_from_bvh(bvh, mo);
  const int kept = bvh.frames() - ((tpose && !o.keep_tpose) ? 1 : 0);

  nlohmann::ordered_json j;
  j["file"] = o.file;
  j["format"] = "bvh";
  j["joints"] = bvh.joints.size();
  j["channels"] = bvh.channel_count;
  j["frames"] = bvh.frames();
  j["fps"] = bvh.fps();
  j["duration_s"] = kept * bvh.frame_time;
  j["units"] = units_name(units);
  j["metres_per_unit"] = scale;
  j["up"] = o.up;
  j["tpose_frame0"] = tpose;
  j["tpose_dropped"] = tpose && !o.keep_tpose;
  j["standing_height_m"] = standing_height(motion);
  add_dynamics(j, motion);
  nlohmann::ordered_json canonical;
  for (int k = 0; k < kJointCount; ++k)
    canonical[joint_name(k)] = bvh.joints[std::size_t(map[std::size_t(k)])].name;
  j["canonical"] = canonical;
  nlohmann::json names = nlohmann::json::array();
  for (const BvhJoint& b : bvh.joints) names.push_back(b.name);
  j["joint_names"] = names;
  return j;
}

nlohmann::ordered_json describe_trc(const InfoCli& o) {
  Trc trc = read_trc(o.file);
  MotionOptions mo;
  mo.marker_map = o.marker_map;
  mo.static_markers = o.static_markers;
  mo.units = parse_units(o.units);
  const std::vector<std::string> names = trc.markers;
  const int frames = trc.frames();
  const double rate = trc.rate_hz, declared = trc.metres_per_unit;
  const double start = trc.time_s.front(), end = trc.time_s.back();
  MarkerReport report;
  const Motion motion = motion_from_trc(std::move(trc), mo, &report);  // the samples released once used
  nlohmann::ordered_json j;
  j["file"] = o.file;
  j["format"] = "trc";
  j["markers"] = names.size();
  j["frames"] = frames;
  j["fps"] = rate;
  j["duration_s"] = end - start + 1 / rate;
  j["start_s"] = start;
  j["metres_per_unit"] = report.metres_per_unit;
  j["units_declared_m"] = declared;
  j["up"] = up_axis_name(report.up_axis);
  j["marker_map"] = report.map;
  nlohmann::ordered_json landmarks;
  for (std::size_t k = 0; k < report.placed.size(); ++k) landmarks[report.placed[k]] = report.placed_by[k];
  j["landmarks"] = landmarks;
  j["calibrated"] = report.calibrated;
  j["methods"] = report.methods;
  j["gap_filled_samples"] = report.gap_filled_frames;
  j["rebuilt_samples"] = report.rebuilt_samples;
  j["stature_m"] = report.stature_m;
  j["stature_from"] = report.stature_from;
  j["upper_body_assumed"] = report.upper_body_assumed;
  j["marker_warnings"] = report.warnings;
  j["treadmill_belt_mps"] = report.belt_speed_mps;
  j["standing_height_m"] = standing_height(motion);
  add_dynamics(j, motion);
  j["marker_names"] = names;
  return j;
}

// A C3D file: what it holds (the number format, points, analog channels,
// force plates, the system that wrote it), then, when its markers place the
// canonical joints, how (as for a .trc file); else why not.
nlohmann::ordered_json describe_c3d(const InfoCli& o) {
  const C3d c = read_c3d(o.file);
  const Trc& trc = c.points;
  nlohmann::ordered_json j;
  j["file"] = o.file;
  j["format"] = "c3d";
  j["number_format"] = c3d_format_name(c.format);
  j["storage"] = c.float_storage ? "float" : "integer";
  j["written_by"] = c.manufacturer;
  j["markers"] = trc.markers.size();
  j["frames"] = trc.frames();
  j["first_frame"] = c.first_frame;
  j["fps"] = trc.rate_hz;
  j["start_s"] = trc.time_s.front();
  j["duration_s"] = trc.frames() / trc.rate_hz;
  j["units"] = c.units;
  j["metres_per_unit"] = trc.metres_per_unit;
  j["analog"] = {{"channels", c.analog.channels()}, {"rate_hz", c.analog.rate_hz}, {"labels", c.analog.labels}};
  nlohmann::ordered_json plates = nlohmann::ordered_json::array();
  for (const C3dPlate& p : c.plates) {
    nlohmann::ordered_json corners = nlohmann::ordered_json::array();
    for (const Eigen::Vector3d& k : p.corners) corners.push_back({k.x(), k.y(), k.z()});
    std::vector<std::string> channels;
    for (int ch : p.channels) channels.push_back(c.analog.labels[std::size_t(ch)]);
    plates.push_back({{"type", p.type}, {"corners_m", corners}, {"channels", channels},
                      {"calibration_matrix", !p.cal_matrix.empty()}});
  }
  j["plates"] = plates;
  if (!c.plates_problem.empty()) j["plates_problem"] = c.plates_problem;
  MotionOptions mo;
  mo.marker_map = o.marker_map;
  mo.static_markers = o.static_markers;
  MarkerReport report;
  try {
    const Motion motion = motion_from_trc(trc, mo, &report);
    j["up"] = up_axis_name(report.up_axis);
    j["marker_map"] = report.map;
    j["landmarks"] = report.placed;
    j["methods"] = report.methods;
    j["gap_filled_samples"] = report.gap_filled_frames;
    j["stature_m"] = report.stature_m;
    j["standing_height_m"] = standing_height(motion);
    add_dynamics(j, motion);
  } catch (const Error& e) {
    j["joints_error"] = e.what();  // the file is still described
  }
  j["marker_names"] = trc.markers;
  return j;
}

nlohmann::ordered_json describe(const InfoCli& o) {
  const std::string ext = lower(std::filesystem::path(o.file).extension().string());
  if (ext == ".bvh") return describe_bvh(o);
  if (ext == ".trc") return describe_trc(o);
  if (ext == ".c3d") return describe_c3d(o);
  // New file types: one branch here, one describe_<type>() above.
  throw Error::in(o.file, "unsupported file type '" + (ext.empty() ? std::string("(none)") : ext) +
                              "' (ptnet info reads .bvh, .trc, .c3d and .h5)");
}

// "r_asis R.ASIS, l_asis L.ASIS, ..." a few to a line.
void print_landmarks(std::ostringstream& s, const nlohmann::ordered_json& landmarks) {
  std::string line;
  const char* label = "  landmarks         ";
  for (const auto& [k, v] : landmarks.items()) {
    const std::string item = k + ": " + v.get<std::string>();
    if (!line.empty() && line.size() + item.size() > 70) {
      s << label << line << ",\n";
      label = "                    ";
      line.clear();
    }
    line += (line.empty() ? "" : ", ") + item;
  }
  if (!line.empty()) s << label << line << "\n";
}

void print_trc(const nlohmann::ordered_json& j) {
  std::ostringstream s;
  s << std::fixed;
  s << j["file"].get<std::string>() << ": markers (.trc)\n";
  s << "  markers           " << j["markers"].get<int>() << ", map " << j["marker_map"].get<std::string>() << " ("
    << j["landmarks"].size() << " landmarks)\n";
  s << "  frames            " << j["frames"].get<int>() << " from " << std::setprecision(3)
    << j["start_s"].get<double>() << " s\n";
  s << "  fps               " << std::setprecision(3) << j["fps"].get<double>() << "\n";
  s << "  duration          " << std::setprecision(2) << j["duration_s"].get<double>() << " s\n";
  s << "  units             " << std::setprecision(5) << j["metres_per_unit"].get<double>() << " m per unit, up "
    << j["up"].get<std::string>() << "\n";
  s << "  stature (est.)    " << std::setprecision(3) << j["stature_m"].get<double>() << " m, from "
    << j["stature_from"].get<std::string>() << "\n";
  s << "  gap-filled        " << j["gap_filled_samples"].get<int>() << " marker samples\n";
  if (j["rebuilt_samples"].get<int>() > 0)
    s << "  rebuilt           " << j["rebuilt_samples"].get<int>()
      << " landmark samples on their segment's markers (gaps over the longest filled)\n";
  if (j["treadmill_belt_mps"].get<double>() > 0)
    s << "  treadmill         belt " << std::setprecision(2) << j["treadmill_belt_mps"].get<double>()
      << " m/s, removed\n";
  print_landmarks(s, j["landmarks"]);
  for (const auto& c : j["calibrated"]) s << "  from static trial " << c.get<std::string>() << "\n";
  s << "  joints\n";
  for (const auto& m : j["methods"]) s << "    " << m.get<std::string>() << "\n";
  for (const auto& w : j["marker_warnings"]) s << "  warning           " << w.get<std::string>() << "\n";
  print_warnings(s, j);
  std::cout << s.str();
}

void print_c3d(const nlohmann::ordered_json& j) {
  std::ostringstream s;
  s << std::fixed;
  s << j["file"].get<std::string>() << ": C3D (" << j["number_format"].get<std::string>() << ", "
    << j["storage"].get<std::string>() << " storage)\n";
  if (!j["written_by"].get<std::string>().empty()) s << "  written by        " << j["written_by"].get<std::string>() << "\n";
  s << "  markers           " << j["markers"].get<int>() << "\n";
  s << "  frames            " << j["frames"].get<int>() << " from frame " << j["first_frame"].get<int>() << " ("
    << std::setprecision(3) << j["start_s"].get<double>() << " s)\n";
  s << "  fps               " << std::setprecision(3) << j["fps"].get<double>() << "\n";
  s << "  duration          " << std::setprecision(2) << j["duration_s"].get<double>() << " s\n";
  s << "  units             " << j["units"].get<std::string>() << " (" << std::setprecision(5)
    << j["metres_per_unit"].get<double>() << " m per unit)\n";
  s << "  analog            " << j["analog"]["channels"].get<int>() << " channels at " << std::setprecision(1)
    << j["analog"]["rate_hz"].get<double>() << " Hz\n";
  int n = 0;
  for (const auto& p : j["plates"]) {
    s << "  plate " << ++n << "           type " << p["type"].get<int>() << ", corners (m)";
    for (const auto& k : p["corners_m"])
      s << " (" << std::setprecision(3) << k[0].get<double>() << ", " << k[1].get<double>() << ", " << k[2].get<double>() << ")";
    s << "\n";
  }
  if (j.contains("plates_problem")) s << "  plates unusable   " << j["plates_problem"].get<std::string>() << "\n";
  if (j.contains("joints_error")) {
    s << "  joints            not placed: " << j["joints_error"].get<std::string>() << "\n";
  } else {
    s << "  marker map        " << j["marker_map"].get<std::string>() << " (" << j["landmarks"].size()
      << " landmarks), up " << j["up"].get<std::string>() << ", stature (est.) " << std::setprecision(3)
      << j["stature_m"].get<double>() << " m\n";
    s << "  joints\n";
    for (const auto& m : j["methods"]) s << "    " << m.get<std::string>() << "\n";
    print_warnings(s, j);
  }
  std::cout << s.str();
}

void print_text(const nlohmann::ordered_json& j) {
  if (j["format"] == "trc") return print_trc(j);
  if (j["format"] == "c3d") return print_c3d(j);
  std::ostringstream s;
  s << std::fixed;
  s << j["file"].get<std::string>() << ": BVH\n";
  s << "  joints            " << j["joints"].get<int>() << " (" << j["channels"].get<int>()
    << " channels)\n";
  s << "  frames            " << j["frames"].get<int>();
  if (j["tpose_frame0"].get<bool>())
    s << (j["tpose_dropped"].get<bool>() ? " (frame 0 is a T-pose, dropped)"
                                         : " (frame 0 is a T-pose, kept)");
  s << "\n";
  s << "  fps               " << std::setprecision(3) << j["fps"].get<double>() << "\n";
  s << "  duration          " << std::setprecision(2) << j["duration_s"].get<double>() << " s\n";
  s << "  units             " << j["units"].get<std::string>() << " (" << std::setprecision(5)
    << j["metres_per_unit"].get<double>() << " m per unit), up " << j["up"].get<std::string>()
    << "\n";
  s << "  standing height   " << std::setprecision(3) << j["standing_height_m"].get<double>()
    << " m\n";
  print_warnings(s, j);
  s << "  canonical joints\n";
  for (const auto& [k, v] : j["canonical"].items())
    s << "    " << std::left << std::setw(16) << k << v.get<std::string>() << "\n";
  std::cout << s.str();
}

void setup(CLI::App& app) {
  auto opt = std::make_shared<InfoCli>();
  CLI::App* cmd =
      app.add_subcommand("info",
                         "Print what a motion file holds (BVH: joints, frames, fps, units, "
                         "standing height, canonical joint mapping; .trc markers: the marker map, "
                         "how each joint was placed; .c3d: markers, analog channels, force plates) or a dataset");
  cmd->add_option("file", opt->file, "Motion file (.bvh, .trc, .c3d) or dataset (.h5)")->required();
  cmd->add_option("--marker-map", opt->marker_map, ".trc, .c3d: a shipped marker map (delaware, plugin-gait, common) or a map file");
  cmd->add_option("--static", opt->static_markers, ".trc, .c3d: the static trial (a .trc file) that calibrates missing joint markers");
  cmd->add_flag("--json", opt->json, "Machine-readable JSON on stdout");
  cmd->add_option("--units", opt->units, "File units: auto|m|cm|mm|in|cmu (.trc: auto reads its Units header)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "m", "cm", "mm", "in", "cmu"}));
  cmd->add_option("--up", opt->up, "Up axis of the file: y|z")
      ->capture_default_str()
      ->check(CLI::IsMember({"y", "z"}));
  cmd->add_flag("--keep-tpose", opt->keep_tpose,
                "Keep a leading T-pose frame (dropped by default)");
  cmd->callback([opt]() {
    const std::string ext = std::filesystem::path(opt->file).extension().string();
    if (ext == ".h5" || ext == ".hdf5") {  // dataset file (data stage)
      std::cout << describe_dataset(Dataset::open(opt->file), opt->json);
      return;
    }
    const nlohmann::ordered_json j = describe(*opt);
    if (opt->json)
      std::cout << j.dump(2) << "\n";
    else
      print_text(j);
  });
}

PTNET_COMMAND(20, setup);

}  // namespace
}  // namespace ptnet::cli::cmd_info
