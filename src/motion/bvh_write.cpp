// BVH writer. Joints are written depth-first from the root (frame columns
// permuted to match), numbers in fixed notation with 6 decimals (trailing
// zeros trimmed): 1e-6 file units and 1e-6 degrees, far inside the 1e-4 m
// round-trip promise for any unit from mm to m.
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

constexpr const char* kChannelNames[] = {"Xposition", "Yposition", "Zposition",
                                         "Xrotation", "Yrotation", "Zrotation"};

void append_number(std::string& out, double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 6);
  char* e = r.ptr;
  while (e > buf && e[-1] == '0') --e;
  if (e > buf && e[-1] == '.') --e;
  if (e - buf == 2 && buf[0] == '-' && buf[1] == '0') {
    out += '0';
    return;
  }
  out.append(buf, e);
}

struct Writer {
  const Bvh& bvh;
  std::vector<std::vector<int>> children;
  std::vector<int> order;  // depth-first
  std::string out;

  void indent(int depth) { out.append(std::size_t(depth), '\t'); }

  void vector3(const Eigen::Vector3d& v) {
    for (int a = 0; a < 3; ++a) {
      out += ' ';
      append_number(out, v[a]);
    }
    out += '\n';
  }

  void joint(int j, int depth) {
    order.push_back(j);
    const BvhJoint& b = bvh.joints[std::size_t(j)];
    indent(depth);
    out += depth == 0 ? "ROOT " : "JOINT ";
    out += b.name;
    out += '\n';
    indent(depth);
    out += "{\n";
    indent(depth + 1);
    out += "OFFSET";
    vector3(b.offset);
    indent(depth + 1);
    out += "CHANNELS " + std::to_string(b.channels.size());
    for (Channel c : b.channels) {
      out += ' ';
      out += kChannelNames[int(c)];
    }
    out += '\n';
    for (int c : children[std::size_t(j)]) joint(c, depth + 1);
    if (b.has_end_site || children[std::size_t(j)].empty()) {
      indent(depth + 1);
      out += "End Site\n";
      indent(depth + 1);
      out += "{\n";
      indent(depth + 2);
      out += "OFFSET";
      vector3(b.has_end_site ? b.end_site : Eigen::Vector3d::Zero());
      indent(depth + 1);
      out += "}\n";
    }
    indent(depth);
    out += "}\n";
  }
};

}  // namespace

std::string format_bvh(const Bvh& bvh) {
  const std::string who = bvh.source.empty() ? "BVH" : bvh.source;
  if (bvh.joints.empty()) throw Error::in(who, "cannot write a BVH without joints");
  if (!(bvh.frame_time > 0) || !std::isfinite(bvh.frame_time))
    throw Error::in(who, "cannot write a BVH with a non-positive frame time");
  if (bvh.channel_count <= 0 || bvh.values.size() % std::size_t(bvh.channel_count) != 0)
    throw Error::in(who, "frame values are not a whole number of frames");
  if (bvh.frames() < 1) throw Error::in(who, "cannot write a BVH without frames");
  Writer w{bvh, std::vector<std::vector<int>>(bvh.joints.size()), {}, {}};
  int root = -1;
  int channels = 0;
  for (std::size_t j = 0; j < bvh.joints.size(); ++j) {
    const BvhJoint& b = bvh.joints[j];
    channels += int(b.channels.size());
    if (b.first_channel < 0 || b.first_channel + int(b.channels.size()) > bvh.channel_count)
      throw Error::in(who, "joint " + b.name + " has channel columns past the frame width");
    if (b.parent < 0) {
      if (root >= 0)
        throw Error::in(who, "more than one ROOT joint (" + bvh.joints[std::size_t(root)].name +
                                 ", " + b.name + ")");
      root = int(j);
    } else if (b.parent >= int(bvh.joints.size()) || b.parent == int(j)) {
      throw Error::in(who, "joint " + b.name + " has an invalid parent");
    } else {
      w.children[std::size_t(b.parent)].push_back(int(j));
    }
  }
  if (root < 0) throw Error::in(who, "no ROOT joint");
  if (channels != bvh.channel_count)
    throw Error::in(who, "channel count does not match the joints' channels");

  w.out.reserve(bvh.values.size() * 10 + bvh.joints.size() * 120 + 256);
  w.out += "HIERARCHY\n";
  w.joint(root, 0);
  if (w.order.size() != bvh.joints.size()) throw Error::in(who, "joints not connected to the ROOT");

  w.out += "MOTION\nFrames: " + std::to_string(bvh.frames()) + "\nFrame Time: ";
  {
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, bvh.frame_time, std::chars_format::general, 10);
    w.out.append(buf, r.ptr);
  }
  w.out += '\n';
  for (int f = 0; f < bvh.frames(); ++f) {
    const double* row = bvh.frame(f);
    bool first = true;
    for (int j : w.order) {
      const BvhJoint& b = bvh.joints[std::size_t(j)];
      for (std::size_t c = 0; c < b.channels.size(); ++c) {
        if (!first) w.out += ' ';
        first = false;
        const double v = row[b.first_channel + int(c)];
        if (!std::isfinite(v))
          throw Error::in(who, "frame " + std::to_string(f) + " of " + b.name + " is not finite");
        append_number(w.out, v);
      }
    }
    w.out += '\n';
  }
  return std::move(w.out);
}

void check_bvh_output(const std::string& path, bool force) {
  check_output_name(path, {".bvh"}, "BVH");
  check_output_path(path, force);
}

void write_bvh(const Bvh& bvh, const std::string& path, bool force) {
  check_bvh_output(path, force);
  write_text_file(path, format_bvh(bvh), force);
}

}  // namespace ptnet
