// A small C3D writer for the tests (see c3d_writer.hpp).
#include "support/c3d_writer.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace ptnet::test {
namespace {

constexpr std::size_t kBlock = 512;

std::string u16_bytes(std::uint16_t v, C3dFormat f) {
  const char lo = char(v & 0xff), hi = char(v >> 8);
  return f == C3dFormat::mips ? std::string{hi, lo} : std::string{lo, hi};
}

// Group and parameter records, each pointing at the next.
class Params {
 public:
  explicit Params(C3dFormat f) : f_(f) {}
  void group(int id, const std::string& name) { record(-id, name, std::string(1, '\0')); }
  void ints(int group, const std::string& name, const std::vector<int>& v, std::vector<int> dims = {}) {
    std::string data;
    for (int x : v) data += u16_bytes(std::uint16_t(std::int16_t(x)), f_);
    param(group, name, 2, dims, data);
  }
  void floats(int group, const std::string& name, const std::vector<double>& v, std::vector<int> dims = {}) {
    std::string data;
    for (double x : v) data += c3d_float_bytes(float(x), f_);
    param(group, name, 4, dims, data);
  }
  void chars(int group, const std::string& name, const std::vector<std::string>& v) {
    std::size_t len = 1;
    for (const std::string& s : v) len = std::max(len, s.size());
    std::string data;
    for (const std::string& s : v) data += s + std::string(len - s.size(), ' ');
    param(group, name, -1, {int(len), int(v.size())}, data);
  }
  void text(int group, const std::string& name, const std::string& s) {
    param(group, name, -1, {int(s.size())}, s);
  }
  // The section: its header, the records (the last one's link 0), padded to blocks.
  std::string section() {
    std::string out = records_;
    if (last_link_ != std::string::npos) out.replace(last_link_, 2, u16_bytes(0, f_));
    out += std::string(2, '\0');  // a zero-length name ends the section too
    const std::size_t blocks = (out.size() + 4 + kBlock - 1) / kBlock;
    std::string head{char(1), char(0x50), char(blocks), char(83 + (f_ == C3dFormat::intel ? 1 : f_ == C3dFormat::dec ? 2 : 3))};
    out = head + out;
    out.resize(blocks * kBlock, '\0');
    return out;
  }

 private:
  void param(int group, const std::string& name, int type, const std::vector<int>& dims, const std::string& data) {
    std::string body{char(type), char(dims.size())};
    for (int d : dims) body += char(d);
    body += data;
    body += '\0';  // no description
    record(group, name, body);
  }
  void record(int id, const std::string& name, const std::string& body) {
    records_ += char(name.size());
    records_ += char(std::int8_t(id));
    records_ += name;
    last_link_ = records_.size();
    records_ += u16_bytes(std::uint16_t(2 + body.size()), f_);
    records_ += body;
  }
  C3dFormat f_;
  std::string records_;
  std::size_t last_link_ = std::string::npos;
};

std::string parameter_section(const C3dSpec& s, int data_block) {
  const int M = int(s.labels.size()), C = int(s.analog_labels.size()), P = int(s.plates.size());
  Params p(s.format);
  p.group(1, "POINT");
  p.ints(1, "USED", {M});
  p.ints(1, "FRAMES", {s.frames});
  p.ints(1, "DATA_START", {data_block});
  p.floats(1, "SCALE", {s.floats ? -s.scale : s.scale});
  p.floats(1, "RATE", {s.rate_hz});
  p.text(1, "UNITS", s.units);
  if (M) p.chars(1, "LABELS", s.labels);
  if (!s.angles.empty()) p.chars(1, "ANGLES", s.angles);
  p.group(2, "ANALOG");
  p.ints(2, "USED", {C});
  if (C) {
    p.floats(2, "RATE", {s.rate_hz * s.per_frame});
    p.floats(2, "GEN_SCALE", {s.gen_scale});
    p.floats(2, "SCALE", s.analog_scale, {C});
    p.ints(2, "OFFSET", std::vector<int>(s.analog_offset.begin(), s.analog_offset.end()), {C});
    p.chars(2, "LABELS", s.analog_labels);
    p.chars(2, "UNITS", s.analog_units);
    p.text(2, "FORMAT", s.unsigned_analog ? "UNSIGNED" : "SIGNED");
  }
  p.group(3, "FORCE_PLATFORM");
  p.ints(3, "USED", {P});
  if (P) {
    std::vector<int> type, channel, zero{s.zero[0], s.zero[1]};
    std::vector<double> corners, origin, cal;
    int rows = 6;
    for (const C3dPlateSpec& q : s.plates) rows = std::max(rows, int(q.channels.size()));
    bool has_cal = false;
    for (const C3dPlateSpec& q : s.plates) {
      type.push_back(q.type);
      for (const auto& c : q.corners) corners.insert(corners.end(), {c.x(), c.y(), c.z()});
      origin.insert(origin.end(), {q.origin.x(), q.origin.y(), q.origin.z()});
      for (int k = 0; k < rows; ++k) channel.push_back(k < int(q.channels.size()) ? q.channels[std::size_t(k)] : 0);
      has_cal = has_cal || !q.cal_matrix.empty();
    }
    for (const C3dPlateSpec& q : s.plates)
      for (int k = 0; k < 36; ++k) cal.push_back(q.cal_matrix.empty() ? (k % 7 == 0) : q.cal_matrix[std::size_t(k)]);
    p.ints(3, "TYPE", type, {P});
    p.ints(3, "ZERO", zero, {2});
    p.floats(3, "CORNERS", corners, {3, 4, P});
    p.floats(3, "ORIGIN", origin, {3, P});
    p.ints(3, "CHANNEL", channel, {rows, P});
    if (has_cal) p.floats(3, "CAL_MATRIX", cal, {6, 6, P});
  }
  if (!s.label_prefix.empty()) {
    p.group(5, "SUBJECTS");
    p.chars(5, "LABEL_PREFIXES", {s.label_prefix});
  }
  if (!s.company.empty() || !s.software.empty()) {
    p.group(4, "MANUFACTURER");
    if (!s.company.empty()) p.text(4, "COMPANY", s.company);
    if (!s.software.empty()) p.text(4, "SOFTWARE", s.software);
  }
  return p.section();
}

std::string value_bytes(double v, const C3dSpec& s, bool analog) {
  if (s.floats) return c3d_float_bytes(float(v), s.format);
  const long n = std::lround(v);
  if (analog && s.unsigned_analog) return u16_bytes(std::uint16_t(n), s.format);
  return u16_bytes(std::uint16_t(std::int16_t(n)), s.format);
}

std::string data_section(const C3dSpec& s) {
  const std::size_t M = s.labels.size(), C = s.analog_labels.size();
  std::string out;
  for (int f = 0; f < s.frames; ++f) {
    for (std::size_t m = 0; m < M; ++m) {
      const Eigen::Vector3d& x = s.xyz[std::size_t(f) * M + m];
      const bool valid = x.allFinite();
      for (int a = 0; a < 3; ++a) out += value_bytes(valid ? (s.floats ? x[a] : x[a] / s.scale) : 0.0, s, false);
      out += value_bytes(valid ? 0.0 : -1.0, s, false);
    }
    for (int k = 0; k < s.per_frame; ++k)
      for (std::size_t c = 0; c < C; ++c)
        out += value_bytes(s.analog[(std::size_t(f) * std::size_t(s.per_frame) + std::size_t(k)) * C + c], s, true);
  }
  return out;
}

}  // namespace

std::string c3d_float_bytes(float value, C3dFormat format) {
  std::uint32_t w;
  if (format == C3dFormat::dec) {
    w = 0;
    if (value != 0) {
      int e = 0;
      const double f = std::frexp(std::abs(double(value)), &e);  // [0.5, 1) x 2^e
      if (e + 128 < 1 || e + 128 > 255) throw std::runtime_error("value out of the DEC float range");
      w = (value < 0 ? 1u << 31 : 0u) | std::uint32_t(e + 128) << 23 | std::uint32_t(std::lround((f - 0.5) * (1 << 24)));
    }
    const std::uint16_t hi = std::uint16_t(w >> 16), lo = std::uint16_t(w & 0xffff);
    return std::string{char(hi & 0xff), char(hi >> 8), char(lo & 0xff), char(lo >> 8)};
  }
  std::memcpy(&w, &value, 4);
  std::string le{char(w & 0xff), char(w >> 8 & 0xff), char(w >> 16 & 0xff), char(w >> 24)};
  return format == C3dFormat::mips ? std::string(le.rbegin(), le.rend()) : le;
}

C3dImage write_c3d(const C3dSpec& s) {
  // The parameter section's size does not depend on the data's block.
  const std::size_t param_blocks = parameter_section(s, 2).size() / kBlock;
  const int data_block = int(2 + param_blocks);
  const std::size_t C = s.analog_labels.size();
  std::string header(kBlock, '\0');
  auto put16 = [&](std::size_t word, int v) { header.replace(2 * word, 2, u16_bytes(std::uint16_t(v), s.format)); };
  header[0] = char(2);
  header[1] = char(0x50);
  put16(1, int(s.labels.size()));
  put16(2, int(C) * s.per_frame);
  put16(3, s.first_frame);
  put16(4, s.first_frame + s.frames - 1);
  header.replace(12, 4, c3d_float_bytes(float(s.floats ? -s.scale : s.scale), s.format));
  put16(8, data_block);
  put16(9, s.per_frame);
  header.replace(20, 4, c3d_float_bytes(float(s.rate_hz), s.format));
  C3dImage img;
  img.bytes = header + parameter_section(s, data_block);
  img.param_start = kBlock;
  img.data_start = img.bytes.size();
  img.frame_bytes = (4 * s.labels.size() + C * std::size_t(s.per_frame)) * (s.floats ? 4 : 2);
  img.bytes += data_section(s);
  return img;
}

}  // namespace ptnet::test
