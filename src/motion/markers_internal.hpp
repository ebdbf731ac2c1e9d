// Internal: the readers' steps on text, the landmarks of a marker map and
// the marker-to-joint steps of motion_from_trc (see ptnet/markers.hpp,
// docs/markers.md).
//
// Dimension legend: F frames, M markers, L = kLandmarkCount landmarks.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ptnet/markers.hpp"

namespace ptnet {

// read_trc on .trc text; errors are one line "walk.trc:7: expected 125 values
// (Frame#, Time, 41 markers x 3), found 80".
Trc parse_trc(std::string_view text, const std::string& source);
// True for a path ending in .trc (any case): load_motion reads it as markers.
bool is_trc_path(const std::string& path);

// The map file format (docs/markers.md): lines "landmark = name name ...",
// '#' comments, "map = NAME" optional. Unknown landmarks are errors that
// list the known ones.
MarkerMap parse_marker_map(std::string_view text, const std::string& source);
std::string marker_map_text(const std::string& name);  // a shipped map's file text
// A shipped map by name ("delaware", "plugin-gait", "common") or a map file
// (unknown landmarks are errors that list the known ones). Users name a map
// by MotionOptions::marker_map.
MarkerMap marker_map(const std::string& name_or_path);

// The landmarks a map can name (docs/markers.md): pelvis r_asis, l_asis,
// r_psis, l_psis, sacrum; per side (r_, l_) knee_lat, knee_med, ankle_lat,
// ankle_med, heel, mt1, mt5, toe, toe_tip, shoulder, elbow_lat, elbow_med,
// wrist_lat, wrist_med, head_front, head_back, temple and the tracking sets
// thigh, shank, foot; trunk c7, t10, clav, sternum, head_top.
const std::vector<std::string>& landmark_names();

}  // namespace ptnet

namespace ptnet::detail {

const std::vector<std::pair<std::string, std::string>>& shipped_marker_maps();  // {name, text}

// Landmarks: the single ones, then the tracking sets (every member used).
enum Landmark : int {
  kRAsis, kLAsis, kRPsis, kLPsis, kSacrum, kC7, kT10, kClav, kSternum, kHeadTop,
  kSided,  // per side from here: side s (0 right, 1 left) adds s * kPerSide
  kKneeLat = kSided, kKneeMed, kAnkleLat, kAnkleMed, kHeel, kMt1, kMt5, kToe, kToeTip, kShoulder, kElbowLat,
  kElbowMed, kWristLat, kWristMed, kHeadFront, kHeadBack, kTemple,
  kSidedEnd,
  kPerSide = kSidedEnd - kSided,
  kLandmarkCount = kSided + 2 * kPerSide
};
enum TrackingSet : int { kThigh, kShank, kFoot, kSetsPerSide };
inline constexpr int kSetCount = 2 * kSetsPerSide;  // [side * kSetsPerSide + set]

// Index of landmark `lm` (kSided <= lm < kSidedEnd) on `side` (0 right, 1 left).
inline int sided(int lm, int side) { return lm + side * kPerSide; }
std::string landmark_name(int landmark);   // "r_knee_lat"
std::string set_name(int set);             // "r_thigh"

// A map resolved against one file's markers: the marker of each landmark
// (-1: absent) and the members of each tracking set.
struct ResolvedMap {
  std::array<int, kLandmarkCount> marker;
  std::array<std::vector<int>, kSetCount> set;
  int found = 0;  // landmarks found
};
ResolvedMap resolve(const MarkerMap& map, const Trc& trc);
// Empty when `r` has what the joints need (pelvis, heels and a toe marker
// on each foot, a trunk marker); else what it lacks ("r_asis (R.ASIS,
// RASI)").
std::vector<std::string> missing_landmarks(const ResolvedMap& r, const MarkerMap& map);

// Fills the gaps of marker m up to max_gap_s long: cubic Hermite between
// the samples either side (tangents from their neighbours), the nearest
// sample at the ends. Returns the samples filled; throws Error naming the
// marker and the frames for a longer gap.
int fill_gaps(Trc& trc, int m, double max_gap_s);

// Per-frame landmark positions (world, metres, z up); NaN: absent.
using LandmarkFrame = std::array<Eigen::Vector3d, kLandmarkCount>;

// The canonical joints of one frame from its landmarks. `height_m`: the
// subject's stature estimate (for the anthropometric offsets), `leg_m`: the
// longest hip-ankle distance (the knee fallback). `methods`, if given, gets
// one line per joint group saying how it was placed.
Pose joints_from_landmarks(const LandmarkFrame& lm, double height_m, std::vector<std::string>* methods);

}  // namespace ptnet::detail
