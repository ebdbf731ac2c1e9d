// describe_dataset: what `ptnet info data.h5 [--json]` prints.
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ptnet/data.hpp"

namespace ptnet {

namespace {
std::string human_bytes(double bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB"};
  int u = 0;
  while (bytes >= 1000 && u < 4) bytes /= 1000, ++u;
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return buf;
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}
}  // namespace

std::string describe_dataset(const Dataset& d, bool json) {
  const DatasetInfo& info = d.info();
  std::error_code ec;
  const auto file_bytes = std::filesystem::file_size(d.path(), ec);
  long long frames = 0, floor_frames = 0;
  int floors = 0;
  std::map<std::string, int> per_category, per_take;
  std::map<std::string, long long> frames_per_category;
  std::map<std::string, int> per_body;
  std::set<std::string> motions;
  for (const auto& s : d.sequences()) {
    frames += s.frames;
    per_category[s.category]++;
    frames_per_category[s.category] += s.frames;
    per_take[std::to_string(s.take)]++;
    per_body[s.body_id]++;
    motions.insert(s.motion_id);
    if (s.floor) ++floors, floor_frames += s.frames;
  }
  // Everything stored: the sequences and their noise-floor copies.
  const double raw_bytes = double(frames + floor_frames) * info.mat.cells() * sizeof(float);
  int females = 0, males = 0;
  std::map<std::string, int> per_role;
  for (const auto& b : d.bodies()) {
    (b.sex == Sex::male ? males : females)++;
    per_role[b.role]++;
  }

  if (json) {
    nlohmann::ordered_json j;
    j["path"] = d.path();
    j["format"] = kDatasetFormat;
    j["version"] = kDatasetVersion;
    j["generator"] = info.generator;
    j["fps"] = info.fps;
    j["mat"] = {{"rows", info.mat.rows}, {"cols", info.mat.cols}, {"pitch_m", info.mat.pitch_m}};
    j["units"] = "kPa";
    j["file_bytes"] = ec ? 0 : file_bytes;
    j["raw_float32_bytes"] = raw_bytes;
    j["frames"] = frames;
    j["seconds"] = frames / info.fps;
    j["motions"] = motions.size();
    j["floor_copies"] = floors;
    j["categories"] = nlohmann::ordered_json::object();
    for (const auto& [c, n] : per_category)
      j["categories"][c] = {{"sequences", n}, {"frames", frames_per_category[c]}};
    j["takes"] = per_take;
    auto& bodies = j["bodies"] = nlohmann::ordered_json::array();
    for (const auto& b : d.bodies())
      bodies.push_back({{"id", b.id}, {"sex", b.sex == Sex::male ? "male" : "female"},
                        {"height_cm", b.height_cm}, {"weight_kg", b.weight_kg}, {"role", b.role},
                        {"sequences", per_body[b.id]}});
    auto& seqs = j["sequences"] = nlohmann::ordered_json::array();
    for (const auto& s : d.sequences())
      seqs.push_back({{"name", s.name}, {"body_id", s.body_id}, {"motion_id", s.motion_id},
                      {"performer", s.performer}, {"category", s.category}, {"take", s.take},
                      {"frames", s.frames}, {"source", s.source}});
    nlohmann::ordered_json cfg = nlohmann::ordered_json::parse(info.config_json, nullptr, false);
    j["config"] = cfg.is_discarded() ? nlohmann::ordered_json(info.config_json) : cfg;
    return j.dump(2) + "\n";
  }

  std::ostringstream o;
  o << d.path() << ": ptnet dataset v" << kDatasetVersion;
  if (!info.generator.empty()) o << " (" << info.generator << ")";
  o << "\n";
  o << "  mat        " << info.mat.rows << " x " << info.mat.cols << " cells, pitch "
    << fmt("%.3g", info.mat.pitch_m * 100) << " cm (" << fmt("%.2f", info.mat.rows * info.mat.pitch_m)
    << " x " << fmt("%.2f", info.mat.cols * info.mat.pitch_m) << " m), kPa float32\n";
  o << "  fps        " << fmt("%g", info.fps) << "\n";
  o << "  bodies     " << d.bodies().size() << " (" << females << " female, " << males << " male";
  bool first_role = true;
  for (const auto& [role, n] : per_role) o << (first_role ? "; " : ", ") << n << " " << role, first_role = false;
  o << ")\n";
  o << "  sequences  " << d.sequences().size() << " (" << motions.size() << (motions.size() == 1 ? " motion), " : " motions), ") << frames
    << " frames, " << fmt("%.1f", frames / info.fps / 60) << " min\n";
  if (!per_category.empty()) {
    o << "  categories";
    bool first = true;
    for (const auto& [c, n] : per_category) {
      o << (first ? " " : ", ") << (c.empty() ? "(none)" : c) << " " << n;
      first = false;
    }
    o << "\n  takes     ";
    first = true;
    for (const auto& [t, n] : per_take) {
      o << (first ? " " : ", ") << "take " << t << " " << n;
      first = false;
    }
    o << "\n";
  }
  if (floors > 0)
    o << "  floor      " << floors << " noise-floor copies (/floor: second sensor seed, for ptnet evaluate)\n";
  o << "  file       " << (ec ? std::string("?") : human_bytes(double(file_bytes)));
  if (!ec && file_bytes > 0 && raw_bytes > 0)
    o << " (raw float32 " << human_bytes(raw_bytes) << ", compression "
      << fmt("%.1f", raw_bytes / double(file_bytes)) << "x)";
  o << "\n";
  if (!d.bodies().empty()) {
    o << "\n  body        sex     height_cm  weight_kg  role        sequences\n";
    for (const auto& b : d.bodies()) {
      char line[160];
      std::snprintf(line, sizeof line, "  %-10s  %-6s  %9.1f  %9.1f  %-10s  %9d\n", b.id.c_str(),
                    b.sex == Sex::male ? "male" : "female", b.height_cm, b.weight_kg,
                    b.role.c_str(), per_body[b.id]);
      o << line;
    }
  }
  return o.str();
}

}  // namespace ptnet
