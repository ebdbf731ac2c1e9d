// Marker maps: the map file format, the shipped maps, and a map resolved
// against a file's markers. Names match as a person reads them
// (marker_key): case and the separators . _ - and space ignored, a side
// word (Right, Left) or a trailing side (ASIS_R) read as the prefix R / L;
// a name ending in '*' matches that name followed by a number (RTH* matches
// RTH1, r_thigh12). The name as spelled wins over one that matches by key.
#include <algorithm>
#include <filesystem>
#include <string>
#include <unordered_map>

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

bool separator(char c) { return c == '.' || c == '_' || c == '-' || c == ' '; }

// A map's name as it matches: its key, and whether a number follows ('*').
struct Pattern {
  std::string key;
  bool numbered = false;
  bool matches(const std::string& marker_key) const {
    if (!numbered) return marker_key == key;
    if (marker_key.size() <= key.size() || marker_key.compare(0, key.size(), key) != 0) return false;
    return std::all_of(marker_key.begin() + std::ptrdiff_t(key.size()), marker_key.end(),
                       [](char c) { return c >= '0' && c <= '9'; });
  }
};

Pattern pattern_of(const std::string& name) {
  const bool numbered = !name.empty() && name.back() == '*';
  return {marker_key(numbered ? std::string_view(name).substr(0, name.size() - 1) : std::string_view(name)), numbered};
}

// The file's markers by name and by key.
struct MarkerIndex {
  std::unordered_map<std::string, int> by_name;
  std::vector<std::string> keys;  // [M]
  explicit MarkerIndex(const std::vector<std::string>& markers) {
    for (std::size_t m = 0; m < markers.size(); ++m) {
      by_name.emplace(markers[m], int(m));
      keys.push_back(marker_key(markers[m]));
    }
  }
  // The markers `name` matches: the one spelled so, else every one whose key matches.
  std::vector<int> match(const std::string& name) const {
    if (const auto it = by_name.find(name); it != by_name.end()) return {it->second};
    const Pattern p = pattern_of(name);
    std::vector<int> out;
    for (std::size_t m = 0; m < keys.size(); ++m)
      if (p.matches(keys[m])) out.push_back(int(m));
    return out;
  }
};

// The first of `names` the file holds, for landmark `lm`; ambiguity (one
// name matching two markers) is r.problem.
void resolve_single(int lm, const MarkerMapEntry& e, const MarkerIndex& index,
                    const std::vector<std::string>& markers, ResolvedMap& r) {
  for (const std::string& n : e.names) {
    const std::vector<int> m = index.match(n);
    if (m.empty()) continue;
    if (m.size() > 1 && r.problem.empty())
      r.problem = landmark_name(lm) + " is ambiguous: " + escaped(n) + " matches " + escaped(markers[std::size_t(m[0])]) +
                  " and " + escaped(markers[std::size_t(m[1])]) + "; name one in a map file (docs/markers.md)";
    r.marker[std::size_t(lm)] = m[0];
    ++r.found;
    r.exact += index.by_name.count(n) > 0;
    return;
  }
}

}  // namespace

std::string marker_key(std::string_view name) {
  std::vector<std::string> parts(1);
  for (char c : name) {
    if (separator(c)) {
      if (!parts.back().empty()) parts.emplace_back();
      continue;
    }
    parts.back() += c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c;
  }
  if (parts.back().empty()) parts.pop_back();
  auto side = [](const std::string& w) -> std::string {
    if (w == "r" || w == "right") return "r";
    if (w == "l" || w == "left") return "l";
    return "";
  };
  std::string key;
  if (parts.size() >= 2 && !side(parts.back()).empty() && side(parts.front()).empty()) {
    key = side(parts.back());
    parts.pop_back();
  }
  for (const std::string& p : parts) key += p;
  for (const char* word : {"right", "left"})
    if (key.size() > std::char_traits<char>::length(word) && key.rfind(word, 0) == 0)
      key = std::string(1, word[0]) + key.substr(std::char_traits<char>::length(word));
  return key;
}

std::string landmark_name(int lm) {
  if (lm < kSided) return kSingleNames[lm];
  const int side = (lm - kSided) / kPerSide;
  return std::string(side == 0 ? "r_" : "l_") + kSidedNames[(lm - kSided) % kPerSide];
}

std::string set_name(int set) {
  return std::string(set / kSetsPerSide == 0 ? "r_" : "l_") + kSetNames[set % kSetsPerSide];
}

std::string bounded_list(const std::vector<std::string>& items, std::size_t max_chars, std::string_view sep,
                         std::size_t item_chars) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string item = escaped(items[i], item_chars, false);
    if (out.size() + item.size() > max_chars) return out + (out.empty() ? "" : std::string(sep)) + "... (" +
                                                       std::to_string(items.size() - i) + " more)";
    out += (i ? std::string(sep) : "") + item;
  }
  return out;
}

ResolvedMap resolve(const MarkerMap& map, const std::vector<std::string>& markers) {
  ResolvedMap r;
  r.marker.fill(-1);
  const MarkerIndex index(markers);
  for (const MarkerMapEntry& e : map.entries) {
    const int k = landmark_index(e.landmark);
    if (k < 0) continue;  // parse_marker_map refused it
    if (k < kLandmarkCount) {
      if (r.marker[std::size_t(k)] < 0) resolve_single(k, e, index, markers, r);
      continue;
    }
    auto& members = r.set[std::size_t(k - kLandmarkCount)];
    for (const std::string& n : e.names)
      for (int m : index.match(n))
        if (std::find(members.begin(), members.end(), m) == members.end()) members.push_back(m);
  }
  for (int a = 0; a < kLandmarkCount && r.problem.empty(); ++a)
    for (int b = a + 1; b < kLandmarkCount; ++b)
      if (r.marker[std::size_t(a)] >= 0 && r.marker[std::size_t(a)] == r.marker[std::size_t(b)]) {
        r.problem = "marker " + escaped(markers[std::size_t(r.marker[std::size_t(a)])]) + " is named for both " +
                    landmark_name(a) + " and " + landmark_name(b) + " (map '" + map.name + "')";
        break;
      }
  return r;
}

std::vector<std::string> missing_landmarks(const ResolvedMap& r, const MarkerMap& map) {
  auto names_of = [&](const std::string& landmark) {
    for (const MarkerMapEntry& e : map.entries)
      if (e.landmark == landmark) return " (" + bounded_list(e.names, 40, ", ") + ")";
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
  return out;
}

bool has_trunk(const ResolvedMap& r) {
  for (int lm : {sided(kShoulder, 0), sided(kShoulder, 1), int(kC7), int(kClav), int(kSternum)})
    if (r.marker[std::size_t(lm)] >= 0) return true;
  return false;
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

namespace {

// Per marker key, the landmark (or set) that named it first and its line.
using NameOwners = std::unordered_map<std::string, std::pair<std::string, long>>;
struct MapOwners {
  NameOwners single;  // single landmarks: a name for one only
  NameOwners sided;   // landmarks and sets of a side (r_, l_): a name for one side only
};

// 'r' or 'l' for a landmark or set of a side ("r_thigh", "l_asis"), else 0.
char side_of(const std::string& landmark) {
  return landmark.size() > 2 && landmark[1] == '_' && (landmark[0] == 'r' || landmark[0] == 'l') ? landmark[0] : 0;
}

// A marker serves one side: a name given to a landmark or set of one side and
// to one of the other (r_thigh = L.Thigh.Upper beside l_thigh's) is refused at
// its line; within one side a name may serve several (a knee marker in the
// thigh and shank sets).
void check_one_side(const std::string& key, const std::vector<std::string>& names, const std::string& source, long n,
                    NameOwners& sided) {
  const char side = side_of(key);
  if (side == 0) return;
  for (const std::string& name : names) {
    const auto [it, fresh] = sided.emplace(detail::marker_key(name), std::make_pair(key, n));
    if (!fresh && side_of(it->second.first) != side)
      throw Error::at(source, n, "each marker name on one side",
                      escaped(name) + " for " + key + " and for " + it->second.first + " (line " +
                          std::to_string(it->second.second) + ")");
  }
}

// One map line "landmark = names" into `map`, its names checked against
// those of the lines before (`owners`).
void add_map_line(MarkerMap& map, std::string_view text, const std::string& source, long n, MapOwners& owners) {
  std::string line(text.substr(0, text.find('#')));
  line = trim(line);
  if (line.empty()) return;
  const std::size_t eq = line.find('=');
  if (eq == std::string::npos) throw Error::at(source, n, "landmark = marker names", escaped(line));
  const std::string key = trim(line.substr(0, eq));
  const std::vector<std::string> names = split_blanks(std::string_view(line).substr(eq + 1));
  if (key == "map") {
    if (names.size() != 1) throw Error::at(source, n, "map = one name", escaped(line));
    map.name = names[0];
    return;
  }
  const int index = detail::landmark_index(key);
  if (index < 0) throw Error::at(source, n, "a landmark (" + join(landmark_names(), ", ") + ")", escaped(key));
  if (names.empty()) throw Error::at(source, n, "at least one marker name after '='", "none");
  for (const MarkerMapEntry& e : map.entries)
    if (e.landmark == key) throw Error::at(source, n, "each landmark once", escaped(key) + " again");
  if (index < detail::kLandmarkCount)  // a single landmark: its names are no other's
    for (const std::string& name : names) {
      const auto [it, fresh] = owners.single.emplace(detail::marker_key(name), std::make_pair(key, n));
      if (!fresh && it->second.first != key)
        throw Error::at(source, n, "each marker name for one landmark",
                        escaped(name) + " for " + key + " and for " + it->second.first + " (line " +
                            std::to_string(it->second.second) + ")");
    }
  check_one_side(key, names, source, n, owners.sided);
  map.entries.push_back({key, names});
}

}  // namespace

MarkerMap parse_marker_map(std::string_view text, const std::string& source) {
  MarkerMap map;
  map.name = std::filesystem::path(source).stem().string();
  MapOwners owners;
  LineReader lines(text);
  for (std::string_view line; lines.next(line);) add_map_line(map, line, source, lines.number(), owners);
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
