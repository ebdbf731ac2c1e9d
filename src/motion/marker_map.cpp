// Marker maps: the map file format, the shipped maps, and a map resolved
// against a file's markers.
#include <algorithm>
#include <filesystem>
#include <string>
#include <unordered_set>

#include "markers_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace detail {
namespace {

const char* const kSingleNames[kSided] = {"r_asis", "l_asis", "r_psis", "l_psis", "sacrum",
                                          "c7",     "t10",    "clav",   "sternum", "head_top"};
const char* const kSidedNames[kPerSide] = {"knee_lat", "knee_med", "ankle_lat", "ankle_med", "heel", "mt1",
                                           "mt5",      "toe",      "toe_tip",   "shoulder",  "elbow_lat",
                                           "elbow_med", "wrist_lat", "wrist_med", "head_front", "head_back",
                                           "temple"};
const char* const kSetNames[kSetsPerSide] = {"thigh", "shank", "foot"};

// -1 if `name` is no landmark; kLandmarkCount + set for a tracking set.
int landmark_index(const std::string& name) {
  for (int i = 0; i < kLandmarkCount; ++i)
    if (landmark_name(i) == name) return i;
  for (int s = 0; s < kSetCount; ++s)
    if (set_name(s) == name) return kLandmarkCount + s;
  return -1;
}

}  // namespace

std::string landmark_name(int lm) {
  if (lm < kSided) return kSingleNames[lm];
  const int side = (lm - kSided) / kPerSide;
  return std::string(side == 0 ? "r_" : "l_") + kSidedNames[(lm - kSided) % kPerSide];
}

std::string set_name(int set) {
  return std::string(set / kSetsPerSide == 0 ? "r_" : "l_") + kSetNames[set % kSetsPerSide];
}

ResolvedMap resolve(const MarkerMap& map, const Trc& trc) {
  ResolvedMap r;
  r.marker.fill(-1);
  for (const MarkerMapEntry& e : map.entries) {
    const int k = landmark_index(e.landmark);
    if (k < 0) continue;  // parse_marker_map refused it
    if (k >= kLandmarkCount) {
      auto& members = r.set[std::size_t(k - kLandmarkCount)];
      for (const std::string& n : e.names) {
        const int m = trc.find(n);
        if (m >= 0 && std::find(members.begin(), members.end(), m) == members.end()) members.push_back(m);
      }
      continue;
    }
    if (r.marker[std::size_t(k)] >= 0) continue;
    for (const std::string& n : e.names) {
      const int m = trc.find(n);
      if (m >= 0) {
        r.marker[std::size_t(k)] = m;
        ++r.found;
        break;
      }
    }
  }
  return r;
}

std::vector<std::string> missing_landmarks(const ResolvedMap& r, const MarkerMap& map) {
  auto names_of = [&](const std::string& landmark) {
    for (const MarkerMapEntry& e : map.entries)
      if (e.landmark == landmark) return " (" + join(e.names, ", ") + ")";
    return std::string(" (not in the map)");
  };
  std::vector<std::string> out;
  auto need = [&](std::initializer_list<int> any_of) {
    for (int lm : any_of)
      if (r.marker[std::size_t(lm)] >= 0) return;
    std::string what;
    for (int lm : any_of) what += (what.empty() ? "" : " or ") + landmark_name(lm) + names_of(landmark_name(lm));
    out.push_back(what);
  };
  need({kRAsis});
  need({kLAsis});
  need({kSacrum, kRPsis, kLPsis});
  for (int side = 0; side < 2; ++side) {
    need({sided(kHeel, side)});
    need({sided(kMt1, side), sided(kMt5, side), sided(kToe, side), sided(kToeTip, side)});
  }
  need({sided(kShoulder, 0), sided(kShoulder, 1), kC7, kClav, kSternum});
  return out;
}

}  // namespace detail

const std::vector<std::string>& landmark_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (int i = 0; i < detail::kLandmarkCount; ++i) n.push_back(detail::landmark_name(i));
    for (int s = 0; s < detail::kSetCount; ++s) n.push_back(detail::set_name(s));
    return n;
  }();
  return names;
}

MarkerMap parse_marker_map(std::string_view text, const std::string& source) {
  MarkerMap map;
  map.name = std::filesystem::path(source).stem().string();
  std::unordered_set<std::string> seen;
  long n = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string line(text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos));
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++n;
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    line = trim(line);
    if (line.empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) throw Error::at(source, n, "landmark = marker names", escaped(line));
    const std::string key = trim(line.substr(0, eq));
    const std::vector<std::string> names = split_blanks(std::string_view(line).substr(eq + 1));
    if (key == "map") {
      if (names.size() != 1) throw Error::at(source, n, "map = one name", escaped(line));
      map.name = names[0];
      continue;
    }
    if (detail::landmark_index(key) < 0)
      throw Error::at(source, n, "a landmark (" + join(landmark_names(), ", ") + ")", escaped(key));
    if (names.empty()) throw Error::at(source, n, "at least one marker name after '='", "none");
    if (!seen.insert(key).second) throw Error::at(source, n, "each landmark once", escaped(key) + " again");
    map.entries.push_back({key, names});
  }
  if (map.entries.empty()) throw Error::in(source, "no landmarks (expected lines 'landmark = marker names')");
  return map;
}

std::vector<std::string> marker_map_names() {
  std::vector<std::string> out;
  for (const auto& [name, text] : detail::shipped_marker_maps()) out.push_back(name);
  return out;
}

std::string marker_map_text(const std::string& name) {
  for (const auto& [n, text] : detail::shipped_marker_maps())
    if (n == name) return text;
  throw Error("marker map '" + name + "' is not shipped (" + join(marker_map_names(), ", ") + ")");
}

MarkerMap marker_map(const std::string& name_or_path) {
  for (const auto& [n, text] : detail::shipped_marker_maps())
    if (n == name_or_path) return parse_marker_map(text, n + ".map");
  if (!std::filesystem::exists(name_or_path))
    throw Error::in(name_or_path, "no such marker map file (shipped maps: " + join(marker_map_names(), ", ") + ")",
                    ErrorKind::not_found);
  note_input(name_or_path);
  return parse_marker_map(read_text_file(name_or_path, 1 << 20), name_or_path);
}

}  // namespace ptnet
