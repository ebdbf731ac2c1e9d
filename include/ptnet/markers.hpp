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
//    present; with no trunk marker (a lower-body set), upright above the
//    pelvis at the canonical proportions, the arms hanging.
// A marker set is a MarkerMap: landmark -> marker names (alternatives; the
// first the file has is used), matched ignoring case and the separators
// . _ - and space (R.ASIS = r_asis = RASIS). Maps for the Delaware /
// gait2354 set, Vicon Plug-in Gait and a common vocabulary of the usual
// names (RASI, R.ASIS, r_calc, RHEE, R.MT5, r_5meta, RP5MT, ...) ship with
// ptnet (marker_map_names()).
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

// Reads a .trc file as OpenSim's TRCFileAdapter does, and more (header
// values padded with spaces and doubled tabs, space-separated files, blank
// lines, CRLF: docs/markers.md); DataRate is checked against the Time
// column. Errors are one line "walk.trc:7: expected 125 values (Frame#,
// Time, 41 markers x 3), found 80".
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

// The shipped maps' names ("delaware", "plugin-gait", "common"); a map file
// is docs/markers.md's "landmark = name name ..." lines.
std::vector<std::string> marker_map_names();
// The marker_map of line `line` of a list (a clips or trials CSV) whose
// files are relative to `folder`: a shipped map's name stays that name; a
// map file is resolved and checked at its line as the list's other files
// (listed_input, ptnet/io.hpp: "t.csv:3: marker_map 'x.map': no such file
// (shipped maps: common, delaware, plugin-gait)"), before any work.
std::string marker_map_in(const std::string& list, long line, const std::string& folder,
                          const std::string& name_or_path);

// ------------------------------------------------------- markers -> joints

// How a file's markers became joints, for `ptnet info` and messages.
struct MarkerReport {
  std::string map;                         // the map used
  std::vector<std::string> placed;         // landmarks found (after calibration)
  std::vector<std::string> placed_by;      // [placed] the file's marker that placed each ("R.ASIS";
                                           // a rebuilt one: "r_mknee (static trial)")
  std::vector<std::string> calibrated;     // landmarks rebuilt from the static trial
  std::vector<std::string> methods;        // one line per joint group: "knee: epicondyles midpoint"
  std::vector<std::string> warnings;       // what was assumed (the upper body of a lower-body set)
  int gap_filled_frames = 0;               // marker samples gap-filled
  int rebuilt_samples = 0;                 // landmark samples rebuilt on their segment's markers (long gaps)
  UpAxis up_axis = UpAxis::y;              // the lab's vertical (detected)
  double metres_per_unit = 0;              // the trial's unit (its Units, or options.units / metres_per_unit)
  double stature_m = 0;                    // the subject's estimated stature (the offsets' H)
  std::string stature_from;                // how: "static trial (median standing hip height)", ...
  bool upper_body_assumed = false;         // no trunk marker: trunk, head and arms placed from the pelvis
  double belt_speed_mps = 0;               // treadmill belt found (0: none), removed when options.remove_belt
  // The belt's velocity (world x, y; m/s): a motion read without removing
  // it (the lab's positions) is the one read with it removed after
  // without_belt(motion, belt_velocity_mps) (zero: no belt).
  Eigen::Vector2d belt_velocity_mps = Eigen::Vector2d::Zero();
};

// The canonical joints of a marker recording, as motion_from_bvh gives them
// for a BVH file: z-up world (the lab's vertical axis detected), metres,
// resampled to options.fps, grounded, a treadmill belt removed.
//  - Units: the file's Units, or options.metres_per_unit / options.units
//    when given; checked against the data (the ASIS 0.15-0.40 m apart), an
//    Error with the unit that fits otherwise.
//  - Names: the map of options.marker_map, else the shipped map that places
//    the file and finds the most landmarks (ties: the one spelling more of
//    the file's names as the file does). A name matching two markers, or a
//    marker named for two landmarks, is an Error.
//  - Gaps: filled (cubic) up to options.max_gap_s; a landmark's longer gap
//    is rebuilt on its segment's other markers (3 needed) and a tracking
//    marker's is left out of the fits in those frames; an Error names the
//    landmark and the frames where neither can place it.
//  - options.static_markers, read once, of the same marker set and scale
//    (else an Error): rebuilds the landmarks the trial lacks, gives the
//    stature and levels the feet. Without one the stature comes from the
//    frames where the subject stands tallest.
//  - Without a trunk marker the trunk stands upright above the pelvis, the
//    head above it, the arms hang (a warning in `report`).
// `report`, if given, says how.
Motion motion_from_trc(const Trc& trc, const MotionOptions& options, MarkerReport* report = nullptr);
// The same, releasing the file's samples once the markers it uses are taken
// (load_motion's memory: the file's samples and the motion are never held
// together).
Motion motion_from_trc(Trc&& trc, const MotionOptions& options, MarkerReport* report = nullptr);

}  // namespace ptnet
