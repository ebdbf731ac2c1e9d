// Internal: the readers' steps on text, the landmarks of a marker map and
// the marker-to-joint steps of motion_from_trc (see ptnet/markers.hpp,
// docs/markers.md).
//
// Dimension legend: F frames, M markers, L = kLandmarkCount landmarks.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ptnet/error.hpp"
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

// The key a marker name matches by: lower case, without the separators
// . _ - and space; a side word (Right, Left) or a trailing side (ASIS_R,
// heel.left) read as the prefix r / l. "R.ASIS", "r_asis", "RightASIS" and
// "ASIS_R" are all "rasis".
std::string marker_key(std::string_view name);
// The items joined with `sep`, each escaped and cut to `item_chars`
// characters, the whole cut to about `max_chars` with "... (N more)": names
// in a message.
std::string bounded_list(const std::vector<std::string>& items, std::size_t max_chars, std::string_view sep = " ",
                         std::size_t item_chars = 32);

// A map resolved against one file's markers: the marker of each landmark
// (-1: absent) and the members of each tracking set.
struct ResolvedMap {
  std::array<int, kLandmarkCount> marker;
  std::array<std::vector<int>, kSetCount> set;
  int found = 0;        // landmarks found
  int exact = 0;        // of them, by a name spelled as the file spells it
  std::string problem;  // one name matching two markers, or one marker for two landmarks ("": none)
};
ResolvedMap resolve(const MarkerMap& map, const std::vector<std::string>& markers);
// Empty when `r` has what the joints need (both ASIS, the sacrum or a PSIS,
// a heel and a toe marker on each foot); else what it lacks ("r_asis
// (R.ASIS, RASI)").
std::vector<std::string> missing_landmarks(const ResolvedMap& r, const MarkerMap& map);
// True when `r` places a trunk marker (an acromion, C7, clavicle or
// sternum); else the upper body is assumed (joints_from_landmarks).
bool has_trunk(const ResolvedMap& r);

// ------------------------------------------------------------ marker tracks

// The markers a recording's landmarks and tracking sets use, in metres and
// world axes (z up), single precision, one array per marker: what
// motion_from_trc works on (the file's other markers and units dropped).
struct Tracks {
  int frames = 0;
  double rate_hz = 0;
  std::vector<std::string> names;                 // [U] the file's marker names
  std::vector<std::vector<Eigen::Vector3f>> xyz;  // [U][F]; NaN: missing
  int count() const { return int(names.size()); }
  Eigen::Vector3f& at(int f, int u) { return xyz[std::size_t(u)][std::size_t(f)]; }
  const Eigen::Vector3f& at(int f, int u) const { return xyz[std::size_t(u)][std::size_t(f)]; }
  bool has(int f, int u) const { return std::isfinite(at(f, u).x()); }
};
// The map's landmarks and sets as tracks: landmark -> track (-1: absent),
// set -> tracks.
struct TrackMap {
  std::array<int, kLandmarkCount> landmark;
  std::array<std::vector<int>, kSetCount> set;
};

// A gap of a track: frames [begin, end).
struct Gap {
  int begin = 0, end = 0;
};
// Fills the gaps of track u up to max_gap_s long: cubic Hermite between
// the samples either side (tangents from their neighbours), the nearest
// sample at the ends. Returns the samples filled; the longer gaps are
// appended to `long_gaps` (left missing). A track with no sample is one
// long gap.
int fill_gaps(Tracks& t, int u, double max_gap_s, std::vector<Gap>* long_gaps);

// A segment's markers for rebuilding one landmark: tracks and their
// positions in a reference pose (static trial, or a frame of the trial).
struct Cluster {
  std::string name;                 // "r_thigh", for messages
  std::vector<int> members;         // tracks
  std::vector<Eigen::Vector3d> ref; // [members] reference positions; NaN: not in the reference
  Eigen::Vector3d target;           // the landmark in the reference pose
};
// The landmark in frame f from the first cluster with at least 3 members
// in the frame and in the reference, not on one line: a rigid fit of their
// reference positions onto the frame's (Umeyama, no scaling, Cappozzo et
// al. 1995). NaN when no cluster can.
Eigen::Vector3d rebuild(const Tracks& t, int f, const std::vector<Cluster>& clusters);
// The tracking sets and landmarks that move with `landmark`'s segment, in
// order of preference (knee: thigh then shank; ankle: shank then foot;
// foot landmarks: the foot; pelvis landmarks: the pelvis markers), each
// named ("r_thigh", "pelvis"). They may hold the landmark's own track.
struct Segment {
  std::string name;
  std::vector<int> tracks;
};
std::vector<Segment> segment_tracks(int landmark, const TrackMap& m);
// Frames as the messages give them: 1-based ranges, "15-131, 140" (at
// most a few, then "...").
std::string frame_ranges(const std::vector<int>& frames);

// ------------------------------------------------ a recording, prepared

// A human pelvis: the ASIS markers' distance (m) that checks a file's unit.
inline constexpr Range kPelvisWidthM{0.15, 0.40};

// The q-quantile (0..1) of `v` (NaN when empty).
double quantile(std::vector<double> v, double q);

// Metres per unit of the trial `trc`: `given_mpu` (options) if > 0, else its
// Units; Error when that makes its ASIS markers no human pelvis
// (kPelvisWidthM), naming the unit that fits. `fallback_mpu` (> 0) is tried
// before the error (a static trial: the unit given for its trial).
double trial_scale(const Trc& trc, const ResolvedMap& r, double given_mpu, double fallback_mpu);

// A recording prepared for the joints: the map's markers as tracks (scaled
// by `scale`, the lab's vertical detected and turned to z), gaps up to
// max_gap_s filled.
struct PreparedTrial {
  std::string source;
  double start_s = 0;  // the time of frame 0
  Tracks t;
  TrackMap m;
  UpAxis up = UpAxis::y;
  double metres_per_unit = 0;
  double asis_width_m = 0;                   // median
  int filled = 0;                            // samples gap-filled
  std::vector<std::vector<Gap>> long_gaps;   // [U] the gaps left
};
PreparedTrial prepare_trial(const Trc& trc, const ResolvedMap& r, double scale, double max_gap_s);
// Error: `landmark` (its marker `marker`, "" if none) cannot be placed in
// `frames` (0-based) of `p`: its segments (`clusters`) have fewer than 3
// markers there.
[[noreturn]] void throw_unplaced(const PreparedTrial& p, int landmark, const std::string& marker,
                                 const std::vector<int>& frames, const std::vector<Cluster>& clusters,
                                 double max_gap_s);
// Landmarks and set members whose marker has no sample at all: absent.
void drop_empty_tracks(PreparedTrial& p);

// The static (standing) trial of a recording, read once: prepared as the
// trial, its markers' mean standing positions, the stature and the feet's
// pitch corrections [left, right] it gives.
struct StaticTrial {
  PreparedTrial p;
  std::vector<Eigen::Vector3d> mean;  // [U]; NaN: no sample
  double stature_m = 0;
  std::array<double, 2> foot_pitch{};
};
// Error when the static trial is not of the trial's marker set (the map
// does not place it) or not of its scale (ASIS widths more than 25 % apart).
StaticTrial read_static_trial(const std::string& path, const MarkerMap& map, const PreparedTrial& trial,
                              double given_mpu, double max_gap_s);
// Rebuilds in `trial` the landmarks it lacks and `st` has, on the segment's
// markers; returns them ("r_knee_med (r_thigh)") and adds their tracks.
// Error naming the frames where a rebuilt landmark's segment has too few
// markers.
std::vector<std::string> calibrate(PreparedTrial& trial, const StaticTrial& st, double max_gap_s);

// The stature (m) of a subject standing: the hip joint centres' height
// above the floor (the low foot markers less 30 mm) over the canonical hip
// height (0.530 H), at quantile q over the frames (0.5: a static trial).
double stature_from_frames(const Tracks& t, const TrackMap& m, double q);
// The stature (m) of a subject from a trial that need not stand still or
// on the floor (squats, a box, flight): where it stands tallest, its legs
// straight: the hip joint centre to heel marker distance at its 95th
// percentile over frames and sides, plus the heel marker's 35 mm above the
// floor, over the canonical hip height.
double stature_from_legs(const Tracks& t, const TrackMap& m);

// Per-frame landmark positions (world, metres, z up); NaN: absent.
using LandmarkFrame = std::array<Eigen::Vector3d, kLandmarkCount>;
// An absent marker's coordinate (.trc blanks, C3D's invalid points).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A landmark or marker seen in this frame (an absent one is NaN).
inline bool has(const Eigen::Vector3d& v) { return std::isfinite(v.x()); }
LandmarkFrame landmarks_at(const Tracks& t, const TrackMap& m, int f);

// The hip joint centres [right, left] of a frame (Harrington et al. 2007).
std::array<Eigen::Vector3d, 2> hip_centres(const LandmarkFrame& lm);
// The canonical joints of one frame from its landmarks. `height_m`: the
// subject's stature estimate (for the anthropometric offsets). `methods`,
// if given, gets one line per joint group saying how it was placed.
Pose joints_from_landmarks(const LandmarkFrame& lm, double height_m, std::vector<std::string>* methods);

}  // namespace ptnet::detail
