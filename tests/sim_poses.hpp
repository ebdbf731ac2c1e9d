// Test helpers for the body and sim stages: canonical poses built directly
// from the skeleton numbers of ../ptnet-team.md (independent of the motion
// stage), and a dependency-free PNG writer for looking at pressure maps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet::test {

using u8 = unsigned char;

// Rest pose of a body of height_cm standing at (x, y) facing +x (arms down).
inline Pose rest_pose(double height_cm, double x = 0, double y = 0) {
  const double H = height_cm / 100;
  Pose p;
  auto at = [&](double px, double py, double pz) { return Eigen::Vector3d(x + px, y + py, pz); };
  p[kPelvis] = at(0, 0, 0.530 * H);
  p[kSpine] = at(0, 0, 0.600 * H);
  p[kChest] = at(0, 0, 0.720 * H);
  p[kNeck] = at(0, 0, 0.818 * H);
  p[kHead] = at(0, 0, 0.870 * H);
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? 1 : -1;  // left = +y
    const int hip = side == 0 ? kLeftHip : kRightHip;
    p[hip] = at(0, s * 0.0475 * H, 0.530 * H);
    p[hip + 1] = at(0, s * 0.0475 * H, 0.285 * H);           // knee
    p[hip + 2] = at(0, s * 0.0475 * H, 0.039 * H);           // ankle
    p[hip + 3] = at(0.0790 * H, s * 0.0475 * H, 0.009 * H);  // toe (MTP)
    const int sh = side == 0 ? kLeftShoulder : kRightShoulder;
    p[sh] = at(0, s * 0.1295 * H, 0.818 * H);
    p[sh + 1] = at(0, s * 0.1295 * H, 0.632 * H);
    p[sh + 2] = at(0, s * 0.1295 * H, 0.486 * H);
  }
  return p;
}

// Moves the joints of one leg (hip excluded) by d.
inline void move_leg(Pose& p, bool left, const Eigen::Vector3d& d) {
  const int hip = left ? kLeftHip : kRightHip;
  for (int j = hip + 1; j <= hip + 3; ++j) p[j] += d;
}

// Rotates a pose about the vertical through (cx, cy) by `yaw` radians.
inline void rotate_pose(Pose& p, double yaw, double cx = 0, double cy = 0) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (auto& q : p) {
    const double x = q.x() - cx, y = q.y() - cy;
    q.x() = cx + c * x - s * y;
    q.y() = cy + s * x + c * y;
  }
}

// A kneeling lunge of `body` at (x, y) facing +x: the left foot flat in
// front, the right shank along the floor and the left hand on it beside the
// foot. The right shank's and the left hand's capsules reach sink_m below
// z = 0 (the sole stands on z = 0), so that the knee, the hand and the sole
// all carry load: capsule contact next to a foot.
inline Pose kneel_pose(const Body& body, double x = 0, double y = 0, double sink_m = 0.004) {
  const double H = body.height_m();
  Pose p;
  auto at = [&](double px, double py, double pz) { return Eigen::Vector3d(x + px, y + py, pz); };
  p[kPelvis] = at(0, 0, 0.33 * H);
  p[kSpine] = at(0.01 * H, 0, 0.40 * H);
  p[kChest] = at(0.03 * H, 0, 0.52 * H);
  p[kNeck] = at(0.05 * H, 0, 0.61 * H);
  p[kHead] = at(0.06 * H, 0, 0.66 * H);
  const double yl = 0.0475 * H, ys = 0.1295 * H;
  p[kLeftHip] = at(0, yl, 0.33 * H);
  p[kLeftKnee] = at(0.22 * H, yl, 0.285 * H);
  p[kLeftAnkle] = at(0.20 * H, yl, 0.039 * H);
  p[kLeftToe] = at(0.279 * H, yl, 0.009 * H);
  p[kRightHip] = at(0, -yl, 0.33 * H);
  p[kRightKnee] = at(-0.05 * H, -yl, 0.05 * H);
  p[kRightAnkle] = at(-0.296 * H, -yl, 0.05 * H);
  p[kRightToe] = at(-0.34 * H, -yl, 0.0);
  p[kLeftShoulder] = at(0.05 * H, ys, 0.61 * H);
  p[kLeftElbow] = at(0.12 * H, 0.15 * H, 0.42 * H);
  p[kLeftWrist] = at(0.17 * H, 0.16 * H, 0.25 * H);
  p[kRightShoulder] = at(0.05 * H, -ys, 0.61 * H);
  p[kRightElbow] = at(0.05 * H, -0.13 * H, 0.45 * H);
  p[kRightWrist] = at(0.07 * H, -0.13 * H, 0.31 * H);
  // Lowers joints so that a segment's capsule bottoms out at -sink_m.
  auto lower = [&](int segment, std::initializer_list<int> joints) {
    const PosedBody posed = pose_body(body, p);
    const SegmentShape& s = body.segments()[segment];
    const double bottom = std::min(posed.a[segment].z() - s.radius_a_m, posed.b[segment].z() - s.radius_b_m);
    for (int j : joints) p[j].z() -= bottom + sink_m;
  };
  lower(kSegRightShank, {kRightKnee, kRightAnkle, kRightToe});
  lower(kSegLeftHand, {kLeftElbow, kLeftWrist});
  return p;
}

inline Motion still_motion(const Pose& pose, int frames = 30, double fps = 30) {
  Motion m;
  m.name = "still";
  m.fps = fps;
  m.frames.assign(frames, pose);
  return m;
}

// ---------------------------------------------------------------- PNG out

inline std::uint32_t png_crc(const unsigned char* data, std::size_t n, std::uint32_t crc = 0xffffffffu) {
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc;
}

// Writes an 8-bit RGB image [h, w, 3] as an uncompressed PNG.
inline bool write_rgb_png(const std::string& path, int w, int h, const std::vector<unsigned char>& rgb) {
  std::vector<unsigned char> raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb.begin() + std::size_t(y) * w * 3, rgb.begin() + std::size_t(y + 1) * w * 3);
  }
  std::vector<unsigned char> z{0x78, 0x01};
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  for (std::size_t off = 0; off < raw.size() || off == 0; off += 65535) {
    std::size_t n = std::min<std::size_t>(65535, raw.size() - off);
    z.push_back(off + n >= raw.size() ? 1 : 0);
    z.push_back(n & 0xff), z.push_back(n >> 8), z.push_back(~n & 0xff), z.push_back((~n >> 8) & 0xff);
    z.insert(z.end(), raw.begin() + off, raw.begin() + off + n);
    if (off + n >= raw.size()) break;
  }
  std::uint32_t adler = (b << 16) | a;
  for (int k = 3; k >= 0; --k) z.push_back((adler >> (8 * k)) & 0xff);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  auto be32 = [&](std::uint32_t v) { unsigned char x[4] = {u8(v >> 24), u8(v >> 16), u8(v >> 8), u8(v)}; std::fwrite(x, 1, 4, f); };
  auto chunk = [&](const char* type, const std::vector<unsigned char>& data) {
    be32(std::uint32_t(data.size()));
    std::vector<unsigned char> td(type, type + 4);
    td.insert(td.end(), data.begin(), data.end());
    std::fwrite(td.data(), 1, td.size(), f);
    be32(png_crc(td.data(), td.size()) ^ 0xffffffffu);
  };
  const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  std::fwrite(sig, 1, 8, f);
  std::vector<unsigned char> ihdr{u8(w >> 24), u8(w >> 16), u8(w >> 8), u8(w),
                                  u8(h >> 24), u8(h >> 16), u8(h >> 8), u8(h),
                                  8, 2, 0, 0, 0};
  chunk("IHDR", ihdr);
  chunk("IDAT", z);
  chunk("IEND", {});
  return std::fclose(f) == 0;
}

// Frames of a sequence side by side (row 0 at the top, col 0 on the left),
// each cell `scale` pixels, a heat ramp from 0 to max_kpa.
inline bool write_frames_png(const std::string& path, const PressureSequence& seq,
                             const std::vector<int>& frames, double max_kpa, int scale = 6) {
  const int R = seq.mat.rows, C = seq.mat.cols, gap = 4;
  const int w = int(frames.size()) * (C * scale + gap), h = R * scale;
  std::vector<unsigned char> rgb(std::size_t(w) * h * 3, 255);
  for (std::size_t k = 0; k < frames.size(); ++k)
    for (int r = 0; r < R; ++r)
      for (int c = 0; c < C; ++c) {
        double t = std::min(1.0, seq.at(frames[k], r, c) / max_kpa);
        unsigned char col[3] = {u8(255 * std::min(1.0, 3 * t)),
                                u8(255 * std::min(1.0, std::max(0.0, 3 * t - 1))),
                                u8(255 * std::max(0.0, 3 * t - 2))};
        if (t <= 0) col[0] = col[1] = col[2] = 30;
        for (int y = 0; y < scale; ++y)
          for (int x = 0; x < scale; ++x) {
            std::size_t px = (std::size_t(r * scale + y) * w + k * (C * scale + gap) + c * scale + x) * 3;
            rgb[px] = col[0], rgb[px + 1] = col[1], rgb[px + 2] = col[2];
          }
      }
  return write_rgb_png(path, w, h, rgb);
}

}  // namespace ptnet::test
