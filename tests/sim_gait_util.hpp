// Test helpers for walking on the simulator: stances from the per-foot trace,
// total force and centre of pressure of a frame, footprints of a sequence.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "ptnet/pressure.hpp"
#include "ptnet/sim.hpp"

namespace ptnet::test {

// Sum of pressure x cell area (N) of frame t.
inline double total_force_n(const PressureSequence& s, int t) {
  double sum = 0;
  for (int i = 0; i < s.mat.cells(); ++i) sum += s.frame(t)[i];
  return sum * 1000.0 * s.mat.cell_area_m2();
}

// Centre of pressure (row, col) in cells of frame t; (-1, -1) when empty.
inline Eigen::Vector2d cop_cells(const PressureSequence& s, int t) {
  double w = 0, r = 0, c = 0;
  for (int i = 0; i < s.mat.rows; ++i)
    for (int j = 0; j < s.mat.cols; ++j) {
      const double p = s.at(t, i, j);
      w += p, r += p * i, c += p * j;
    }
  return w > 0 ? Eigen::Vector2d(r / w, c / w) : Eigen::Vector2d(-1, -1);
}

struct Stance {
  int side = 0, first = 0, last = 0;  // frames, inclusive
};

// Runs of frames in which a foot carries more than `min_n`, gaps of up to
// `gap` frames bridged (weight shifts), at least 2 frames long.
inline std::vector<Stance> stances(const std::vector<FrameTrace>& trace, double min_n, int gap = 3) {
  std::vector<Stance> out;
  const int T = int(trace.size());
  for (int side = 0; side < 2; ++side)
    for (int t = 0; t < T;) {
      if (!(trace[t].foot[side].force_n > min_n)) { ++t; continue; }
      int e = t;
      for (;;) {
        int n = e + 1;
        while (n < T && n <= e + gap + 1 && !(trace[n].foot[side].force_n > min_n)) ++n;
        if (n < T && n <= e + gap + 1 && trace[n].foot[side].force_n > min_n) e = n;
        else break;
      }
      if (e > t) out.push_back({side, t, e});
      t = e + 1;
    }
  std::sort(out.begin(), out.end(), [](const Stance& a, const Stance& b) {
    return a.first != b.first ? a.first < b.first : a.side < b.side;
  });
  return out;
}

// Cells with pressure in any frame of [first, last]: the footprint of a stance.
struct Footprint {
  std::vector<Eigen::Vector2d> cells;  // (row, col) centres
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double length_m = 0;  // extent along the principal axis, plus one cell
  double width_m = 0;   // extent across it, plus one cell
};

inline Footprint footprint(const PressureSequence& s, int first, int last) {
  Footprint f;
  std::vector<char> on(std::size_t(s.mat.cells()), 0);
  for (int t = first; t <= last; ++t)
    for (int i = 0; i < s.mat.cells(); ++i)
      if (s.frame(t)[i] > 0) on[std::size_t(i)] = 1;
  for (int i = 0; i < s.mat.cells(); ++i)
    if (on[std::size_t(i)]) f.cells.emplace_back(i / s.mat.cols, i % s.mat.cols);
  if (f.cells.empty()) return f;
  for (const auto& c : f.cells) f.centroid += c;
  f.centroid /= double(f.cells.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& c : f.cells) cov += (c - f.centroid) * (c - f.centroid).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d axis = eig.eigenvectors().col(1), across = eig.eigenvectors().col(0);
  double lo = 1e9, hi = -1e9, alo = 1e9, ahi = -1e9;
  for (const auto& c : f.cells) {
    lo = std::min(lo, axis.dot(c)), hi = std::max(hi, axis.dot(c));
    alo = std::min(alo, across.dot(c)), ahi = std::max(ahi, across.dot(c));
  }
  f.length_m = (hi - lo + 1) * s.mat.pitch_m;
  f.width_m = (ahi - alo + 1) * s.mat.pitch_m;
  return f;
}

// Largest 8-connected region of cells with pressure in frame t: its length
// along its principal axis (m), as footprint() measures it.
inline double largest_region_length_m(const PressureSequence& s, int t) {
  const int R = s.mat.rows, C = s.mat.cols;
  std::vector<int> label(std::size_t(R * C), -1);
  double best = 0;
  std::size_t best_n = 0;
  for (int start = 0; start < R * C; ++start) {
    if (label[std::size_t(start)] >= 0 || !(s.frame(t)[start] > 0)) continue;
    std::vector<int> stack{start}, members;
    label[std::size_t(start)] = start;
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      members.push_back(k);
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
          const int r = k / C + dr, c = k % C + dc;
          if (r < 0 || r >= R || c < 0 || c >= C) continue;
          const int n = r * C + c;
          if (label[std::size_t(n)] < 0 && s.frame(t)[n] > 0) label[std::size_t(n)] = start, stack.push_back(n);
        }
    }
    if (members.size() > best_n) {
      PressureSequence one(s.mat, 1, s.fps);
      for (int k : members) one.kpa[std::size_t(k)] = 1;
      best_n = members.size();
      best = footprint(one, 0, 0).length_m;
    }
  }
  return best;
}

}  // namespace ptnet::test
