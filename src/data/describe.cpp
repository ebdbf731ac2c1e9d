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

// What the listing counts: frames, sequences per category, take and body.
struct Counts {
  long long frames = 0, floor_frames = 0;
  int floors = 0;
  std::map<std::string, int> per_category, per_take, per_body, per_role;
  std::map<std::string, long long> frames_per_category;
  std::set<std::string> motions;
  int females = 0, males = 0;
  double raw_bytes = 0;  // everything stored: the sequences and their noise-floor copies
  std::uintmax_t file_bytes = 0;
  bool file_size_known = false;
};

Counts count(const Dataset& d) {
  Counts n;
  for (const auto& s : d.sequences()) {
    n.frames += s.frames;
    n.per_category[s.category]++;
    n.frames_per_category[s.category] += s.frames;
    n.per_take[std::to_string(s.take)]++;
    n.per_body[s.body_id]++;
    n.motions.insert(s.motion_id);
    if (s.floor) ++n.floors, n.floor_frames += s.frames;
  }
  n.raw_bytes = double(n.frames + n.floor_frames) * d.info().mat.cells() * sizeof(float);
  for (const auto& b : d.bodies()) {
    (b.sex == Sex::male ? n.males : n.females)++;
    n.per_role[b.role]++;
  }
  std::error_code ec;
  n.file_bytes = std::filesystem::file_size(d.path(), ec);
  n.file_size_known = !ec;
  return n;
}

std::string describe_json(const Dataset& d, Counts& n) {
  const DatasetInfo& info = d.info();
  nlohmann::ordered_json j;
  j["path"] = d.path();
  j["format"] = kDatasetFormat;
  j["version"] = kDatasetVersion;
  j["generator"] = info.generator;
  j["fps"] = info.fps;
  j["mat"] = {{"rows", info.mat.rows}, {"cols", info.mat.cols}, {"pitch_m", info.mat.pitch_m}};
  j["units"] = "kPa";
  j["file_bytes"] = n.file_size_known ? n.file_bytes : 0;
  j["raw_float32_bytes"] = n.raw_bytes;
  j["frames"] = n.frames;
  j["seconds"] = n.frames / info.fps;
  j["motions"] = n.motions.size();
  j["floor_copies"] = n.floors;
  j["categories"] = nlohmann::ordered_json::object();
  for (const auto& [c, count] : n.per_category)
    j["categories"][c] = {{"sequences", count}, {"frames", n.frames_per_category[c]}};
  j["takes"] = n.per_take;
  auto& bodies = j["bodies"] = nlohmann::ordered_json::array();
  for (const auto& b : d.bodies())
    bodies.push_back({{"id", b.id}, {"sex", sex_name(b.sex)}, {"height_cm", b.height_cm},
                      {"weight_kg", b.weight_kg}, {"role", b.role}, {"sequences", n.per_body[b.id]}});
  auto& seqs = j["sequences"] = nlohmann::ordered_json::array();
  for (const auto& s : d.sequences())
    seqs.push_back({{"name", s.name}, {"body_id", s.body_id}, {"motion_id", s.motion_id},
                    {"performer", s.performer}, {"category", s.category}, {"take", s.take},
                    {"frames", s.frames}, {"source", s.source}});
  nlohmann::ordered_json cfg = nlohmann::ordered_json::parse(info.config_json, nullptr, false);
  j["config"] = cfg.is_discarded() ? nlohmann::ordered_json(info.config_json) : cfg;
  return j.dump(2) + "\n";
}

// The summary lines: mat, fps, bodies, sequences, categories, file size.
void describe_summary(const Dataset& d, const Counts& n, std::ostringstream& o) {
  const DatasetInfo& info = d.info();
  o << d.path() << ": ptnet dataset v" << kDatasetVersion;
  if (!info.generator.empty()) o << " (" << info.generator << ")";
  o << "\n";
  o << "  mat        " << info.mat.rows << " x " << info.mat.cols << " cells, pitch "
    << fmt("%.3g", info.mat.pitch_m * 100) << " cm (" << fmt("%.2f", info.mat.rows * info.mat.pitch_m)
    << " x " << fmt("%.2f", info.mat.cols * info.mat.pitch_m) << " m), kPa float32\n";
  o << "  fps        " << fmt("%g", info.fps) << "\n";
  o << "  bodies     " << d.bodies().size() << " (" << n.females << " female, " << n.males << " male";
  bool first_role = true;
  for (const auto& [role, count] : n.per_role) o << (first_role ? "; " : ", ") << count << " " << role, first_role = false;
  o << ")\n";
  o << "  sequences  " << d.sequences().size() << " (" << n.motions.size()
    << (n.motions.size() == 1 ? " motion), " : " motions), ") << n.frames << " frames, "
    << fmt("%.1f", n.frames / info.fps / 60) << " min\n";
  if (!n.per_category.empty()) {
    o << "  categories";
    bool first = true;
    for (const auto& [c, count] : n.per_category) {
      o << (first ? " " : ", ") << (c.empty() ? "(none)" : c) << " " << count;
      first = false;
    }
    o << "\n  takes     ";
    first = true;
    for (const auto& [t, count] : n.per_take) {
      o << (first ? " " : ", ") << "take " << t << " " << count;
      first = false;
    }
    o << "\n";
  }
  if (n.floors > 0)
    o << "  floor      " << n.floors << " noise-floor copies (/floor: second sensor seed, for ptnet evaluate)\n";
  o << "  file       " << (n.file_size_known ? human_bytes(double(n.file_bytes)) : std::string("?"));
  if (n.file_size_known && n.file_bytes > 0 && n.raw_bytes > 0)
    o << " (raw float32 " << human_bytes(n.raw_bytes) << ", compression "
      << fmt("%.1f", n.raw_bytes / double(n.file_bytes)) << "x)";
  o << "\n";
}

// The bodies table.
void describe_bodies(const Dataset& d, Counts& n, std::ostringstream& o) {
  if (d.bodies().empty()) return;
  o << "\n  body        sex     height_cm  weight_kg  role        sequences\n";
  for (const auto& b : d.bodies()) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-10s  %-6s  %9.1f  %9.1f  %-10s  %9d\n", b.id.c_str(), sex_name(b.sex),
                  b.height_cm, b.weight_kg, b.role.c_str(), n.per_body[b.id]);
    o << line;
  }
}

}  // namespace

std::string describe_dataset(const Dataset& d, bool json) {
  Counts n = count(d);
  if (json) return describe_json(d, n);
  std::ostringstream o;
  describe_summary(d, n, o);
  describe_bodies(d, n, o);
  return o.str();
}

}  // namespace ptnet
