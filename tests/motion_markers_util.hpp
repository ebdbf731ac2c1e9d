// Test helpers for marker files: .trc text from marker positions, a
// standing body in Delaware / gait2354 names, rigid motions of it.
#pragma once

#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "ptnet/markers.hpp"

namespace ptnet::testing {

using V = Eigen::Vector3d;
namespace fs = std::filesystem;

// A .trc text: markers [F][M] in mm, lab axes Y up (NaN: a blank cell).
inline std::string trc_text(const std::vector<std::string>& names, const std::vector<std::vector<V>>& frames, double rate) {
  std::ostringstream o;
  o << "PathFileType\t4\t(X/Y/Z)\tt.trc\nDataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n"
    << rate << "\t" << rate << "\t" << frames.size() << "\t" << names.size() << "\tmm\nFrame#\tTime";
  for (const auto& n : names) o << "\t" << n << "\t\t";
  o << "\n\t";
  for (std::size_t m = 0; m < names.size(); ++m) o << "\tX" << m + 1 << "\tY" << m + 1 << "\tZ" << m + 1;
  o << "\n\n";
  o.precision(10);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    o << f + 1 << "\t" << f / rate;
    for (const V& p : frames[f])
      for (int a = 0; a < 3; ++a) {
        o << "\t";
        if (std::isfinite(p[a])) o << p[a];
      }
    o << "\n";
  }
  return o.str();
}

inline std::string write_temp(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / ("ptnet_markers_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

// A standing body in Delaware / gait2354 names, lab mm, Y up, facing +X,
// its right towards +Z; knee and ankle markers included.
struct Standing {
  std::vector<std::string> names;
  std::vector<V> at;
  void add(const std::string& n, double x, double y, double z) { names.push_back(n), at.emplace_back(x, y, z); }
  int index(const std::string& n) const { return int(std::find(names.begin(), names.end(), n) - names.begin()); }
};

inline Standing standing() {
  Standing s;
  for (int side = 0; side < 2; ++side) {
    const double k = side == 0 ? 1 : -1;  // right: +Z
    const std::string p = side == 0 ? "R." : "L.";
    s.add(p + "ASIS", 120, 1000, k * 120);
    s.add(p + "Thigh.Upper", 60, 800, k * 150);
    s.add(p + "Thigh.Front", 110, 700, k * 110);
    s.add(p + "Thigh.Rear", 20, 690, k * 140);
    s.add(p + "Knee.Lat", 40, 520, k * 150);
    s.add(p + "Knee.Med", 40, 520, k * 50);
    s.add(p + "Shank.Upper", 60, 400, k * 140);
    s.add(p + "Shank.Front", 90, 300, k * 100);
    s.add(p + "Shank.Rear", 10, 310, k * 130);
    s.add(p + "Ankle.Lat", 0, 80, k * 135);
    s.add(p + "Ankle.Med", 0, 85, k * 65);
    s.add(p + "Heel", -60, 40, k * 100);
    s.add(p + "Midfoot.Sup", 80, 70, k * 90);
    s.add(p + "Midfoot.Lat", 80, 40, k * 135);
    s.add(p + "Toe.Lat", 160, 25, k * 130);
    s.add(p + "Toe.Med", 170, 25, k * 70);
    s.add(p + "Toe.Tip", 220, 20, k * 90);
    s.add(p + "Acromium", 0, 1450, k * 190);
  }
  s.add("V.Sacral", -100, 1000, 0);
  s.add("Sternum", 100, 1350, 0);
  s.add("Top.Head", 0, 1750, 0);
  return s;
}

// `s` moved rigidly per frame: turned about the vertical by 0.3 t rad and
// carried 0.4 t m along X (t in s), at `rate` Hz for `frames` frames.
inline std::vector<std::vector<V>> moved(const Standing& s, int frames, double rate) {
  std::vector<std::vector<V>> out;
  for (int f = 0; f < frames; ++f) {
    const double t = f / rate;
    const Eigen::Matrix3d r = Eigen::AngleAxisd(0.3 * t, V::UnitY()).toRotationMatrix();
    std::vector<V> frame;
    for (const V& p : s.at) frame.push_back(r * p + V(400 * t, 0, 0));
    out.push_back(frame);
  }
  return out;
}

inline ptnet::MotionOptions keep_rate() {
  ptnet::MotionOptions o;
  o.fps = 0;
  o.remove_belt = false;
  return o;
}

}  // namespace ptnet::testing
