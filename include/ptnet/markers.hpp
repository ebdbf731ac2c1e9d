// ptnet/markers.hpp: gait-lab marker files (OpenSim .trc) in, the canonical
// joints out, by documented anatomical methods (docs/markers.md).
//
//   ptnet::Trc trc = ptnet::read_trc("walk.trc");             // markers [F, M], file units
//   ptnet::MotionOptions opt;                                // 30 fps, marker map chosen
//   ptnet::Motion m = ptnet::load_motion("walk.trc", opt);   // as for a BVH file
//   opt.marker_map = "my_lab.map";                           // a lab's own names
//   opt.static_markers = "walk_static.trc";                  // calibrates knee / ankle centres
//
// Joints from landmarks (metres, after the file's units):
//  - pelvis frame from the ASIS and the PSIS (or the sacral marker); hip joint
//    centres by Harrington et al. (2007); pelvis = their midpoint;
//  - knee / ankle / elbow centres: the midpoint of the epicondyle /
//    malleolus / epicondyle markers; with only the lateral one, moved
//    medially by half the joint's anthropometric width; with neither, from a
//    static trial (the missing markers rebuilt on the segment's tracking
//    markers, Cappozzo et al. 1995) or, last, from the leg's geometry;
//  - toe (metatarsophalangeal) joint from the metatarsal-head markers;
//  - trunk, neck, shoulders (Rab et al. 2002), head, wrists from the markers
//    present.
// A marker set is a MarkerMap: landmark -> marker names (alternatives; the
// first the file has is used). Maps for the Delaware / gait2354 set, Vicon
// Plug-in Gait and the common RASI / RCAL / RTOE / RMT5 naming ship with ptnet
// (marker_map_names()).
//
// Dimension legend: F frames, M markers of a file, L landmarks.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ptnet/motion.hpp"

namespace ptnet {

// ------------------------------------------------------------- .trc files

struct Trc {
  std::vector<std::string> markers;  // [M]
  double rate_hz = 0;                // DataRate
  double metres_per_unit = 0.001;    // from Units: mm, cm or m
  std::vector<double> time_s;        // [F], the recording's clock
  std::vector<Eigen::Vector3d> xyz;  // [F, M] file units and axes; NaN: missing (a blank cell)
  std::string source;                // file name, for messages

  int frames() const { return int(time_s.size()); }
  const Eigen::Vector3d& at(int frame, int marker) const { return xyz[std::size_t(frame) * markers.size() + marker]; }
  int find(std::string_view name) const;  // -1 if absent
};

// Reads a .trc file; errors are one line "walk.trc:7: expected 125 values
// (Frame#, Time, 41 markers x 3), found 80".
Trc read_trc(const std::string& path);
// The markers of a .trc file (read_trc) or of a .c3d file (its points,
// read_c3d in ptnet/c3d.hpp), chosen by the extension (any case).
Trc read_markers(const std::string& path);

// ------------------------------------------------------------ marker maps

// One landmark of a map and the marker names that may hold it.
struct MarkerMapEntry {
  std::string landmark;            // e.g. "r_asis"
  std::vector<std::string> names;  // alternatives, or a tracking set's members
};
struct MarkerMap {
  std::string name;  // "delaware", or the file's stem
  std::vector<MarkerMapEntry> entries;
};

// A shipped map by name ("delaware", "plugin-gait", "common") or a map file
// (docs/markers.md: lines "landmark = name name ...", '#' comments, "map =
// NAME" optional; unknown landmarks are errors that list the known ones).
MarkerMap marker_map(const std::string& name_or_path);
std::vector<std::string> marker_map_names();  // the shipped maps

// ------------------------------------------------------- markers -> joints

// How a file's markers became joints, for `ptnet info` and messages.
struct MarkerReport {
  std::string map;                         // the map used
  std::vector<std::string> placed;         // landmarks found (after calibration)
  std::vector<std::string> calibrated;     // landmarks rebuilt from the static trial
  std::vector<std::string> methods;        // one line per joint group: "knee: epicondyles midpoint"
  int gap_filled_frames = 0;               // marker samples gap-filled
  std::string up_axis;                     // "y" or "z" (detected)
  double stature_m = 0;                    // the subject's estimated stature (the offsets' H)
  double belt_speed_mps = 0;               // treadmill belt removed (0: none)
};

// The canonical joints of a marker recording, as motion_from_bvh gives them
// for a BVH file: z-up world (the lab's vertical axis detected), metres,
// resampled to options.fps, grounded. Missing samples are gap-filled (cubic)
// over gaps up to options.max_gap_s; a longer gap of a marker the map uses is
// an error naming the marker and the frames. A file the map cannot place is
// an error listing the markers found. `report`, if given, says how.
Motion motion_from_trc(const Trc& trc, const MotionOptions& options, MarkerReport* report = nullptr);

}  // namespace ptnet
