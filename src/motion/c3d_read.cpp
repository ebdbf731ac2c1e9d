// C3D files (c3d.org, "The C3D File Format User Guide"): block 1 is the
// header (the parameter section's block, the key 0x50, the counts, the
// first and last frame, the scale, the data's block, the rate); the
// parameter section's processor byte gives the number format; the data
// section holds per frame the points (X, Y, Z and a residual word each, as
// 16-bit integers x POINT:SCALE or, when the scale is negative, as floats),
// then the analog samples (sample-major). Every count is checked against
// the file's size before anything is allocated.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "motion/c3d_internal.hpp"
#include "motion/markers_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

using detail::C3dBytes;
using detail::C3dParams;
using detail::kC3dBlock;
using detail::kNaN;

// Where the data are and how many: the header's counts, checked against
// the parameters that repeat them.
struct Layout {
  long points = 0, analog_per_frame = 0;  // values per frame: 4 x points, then analog_per_frame
  long first = 1, frames = 0;
  long channels = 0, per_frame = 0;       // analog channels, samples per frame
  double scale = 0, rate = 0;
  std::size_t data = 0;                   // byte of the first frame
  std::size_t value_bytes = 2, frame_bytes = 0;
};

Error bad(const std::string& source, const std::string& expected, const std::string& found) {
  return Error::in(source, "expected " + expected + ", found " + found);
}

// A stored number as a whole number; `fallback` when it is none in +-2^31.
long whole(double v, long fallback) { return std::isfinite(v) && std::abs(v) < 2147483648.0 ? long(v) : fallback; }

C3dFormat format_of(std::string_view bytes, const std::string& source, std::size_t& param_start) {
  if (bytes.size() < kC3dBlock)
    throw bad(source, "a C3D header of 512 bytes", std::to_string(bytes.size()) + " bytes");
  const int block = static_cast<unsigned char>(bytes[0]), key = static_cast<unsigned char>(bytes[1]);
  if (key != 0x50)
    throw bad(source, "a C3D file (its second byte 0x50)", "byte " + std::to_string(key) + " (not a C3D file?)");
  param_start = std::size_t(block - 1) * kC3dBlock;
  if (block < 2 || param_start + 4 > bytes.size())
    throw bad(source, "the parameter section's block (header byte 1) inside the file",
              "block " + std::to_string(block) + " of a " + std::to_string(bytes.size()) + "-byte file");
  const int processor = static_cast<unsigned char>(bytes[param_start + 3]);
  if (processor == 84) return C3dFormat::intel;
  if (processor == 85) return C3dFormat::dec;
  if (processor == 86) return C3dFormat::mips;
  throw bad(source, "the processor type 84 (Intel), 85 (DEC) or 86 (MIPS) at byte " + std::to_string(param_start + 3),
            std::to_string(processor));
}

// The frame count (c3d.org, "Reading the frame count"): POINT:FRAMES (a
// 16-bit integer read unsigned, or a float); when it is 65535, the count of
// TRIAL:ACTUAL_START_FIELD..ACTUAL_END_FIELD (two 16-bit words each) or
// POINT:LONG_FRAMES; without POINT:FRAMES, the header's first to last frame.
// The first frame (the clock's start) is the header's, or the TRIAL
// group's when the count comes from it.
void read_frames(const C3dBytes& b, const C3dParams& p, Layout& l) {
  l.first = b.u16(6, "the first frame");
  const long last = b.u16(8, "the last frame");
  l.frames = p.count("POINT", "FRAMES", last >= l.first ? last - l.first + 1 : -1);
  const std::vector<double> start = p.numbers("TRIAL", "ACTUAL_START_FIELD"), end = p.numbers("TRIAL", "ACTUAL_END_FIELD");
  auto field = [](const std::vector<double>& v) {
    auto word = [](double x) { return whole(x < 0 ? x + 65536 : x, -1); };
    return word(v[0]) + 65536 * word(v[1]);
  };
  if (l.frames == 65535 && start.size() == 2 && end.size() == 2 && field(end) >= field(start) && field(start) > 0) {
    l.first = field(start);
    l.frames = field(end) - field(start) + 1;
  } else if (l.frames == 65535 && p.find("POINT", "LONG_FRAMES")) {
    l.frames = p.count("POINT", "LONG_FRAMES", -1);
  }
  if (l.frames < 1 || l.first < 1 || l.first > 2147483647 - l.frames)
    throw bad(b.source(), "at least one frame (POINT:FRAMES) from a first frame >= 1",
              std::to_string(l.frames) + " frames from frame " + std::to_string(l.first));
}

// A count of the header, and the parameter that repeats it when present.
long agreed(const C3dBytes& b, const C3dParams& p, std::size_t at, const char* group, const char* name) {
  const long header = b.u16(at, name);
  const long param = p.count(group, name, header);
  if (param != header)
    throw bad(b.source(), std::string(group) + ":" + name + " equal to the header's word " + std::to_string(at / 2 + 1),
              std::to_string(param) + " against " + std::to_string(header));
  return header;
}

Layout read_layout(const C3dBytes& b, const C3dParams& p) {
  Layout l;
  l.points = agreed(b, p, 2, "POINT", "USED");
  l.analog_per_frame = b.u16(4, "the analog values per frame");
  read_frames(b, p, l);
  l.scale = p.number("POINT", "SCALE", b.f32(12, "the point scale"));
  l.rate = p.number("POINT", "RATE", b.f32(20, "the frame rate"));
  if (!std::isfinite(l.scale) || l.scale == 0) throw bad(b.source(), "a non-zero POINT:SCALE", number_text(l.scale));
  if (!(l.rate > 0) || !(l.rate <= 1e6)) throw bad(b.source(), "a POINT:RATE in (0, 1e6] Hz", number_text(l.rate));
  const long data_block = agreed(b, p, 16, "POINT", "DATA_START");
  if (data_block < 2) throw bad(b.source(), "the data's block (POINT:DATA_START) >= 2", std::to_string(data_block));
  l.data = std::size_t(data_block - 1) * kC3dBlock;
  l.channels = l.analog_per_frame ? p.count("ANALOG", "USED", 0) : 0;
  if (l.analog_per_frame > 0 && (l.channels <= 0 || l.analog_per_frame % l.channels != 0))
    throw bad(b.source(), "ANALOG:USED channels dividing the header's " + std::to_string(l.analog_per_frame) +
                              " analog values per frame",
              std::to_string(l.channels));
  l.per_frame = l.channels ? l.analog_per_frame / l.channels : 0;
  l.value_bytes = l.scale < 0 ? 4 : 2;
  l.frame_bytes = std::size_t(4 * l.points + l.analog_per_frame) * l.value_bytes;
  if (l.frame_bytes == 0) throw bad(b.source(), "points or analog channels", "neither (POINT:USED and the analog count 0)");
  const std::uint64_t need = std::uint64_t(l.frames) * l.frame_bytes;  // < 2^32 x 2^21
  if (l.data > b.size() || need > b.size() - l.data)
    throw bad(b.source(), std::to_string(l.frames) + " frames of " + std::to_string(l.frame_bytes) + " bytes from byte " +
                              std::to_string(l.data),
              std::to_string(b.size() > l.data ? b.size() - l.data : 0) + " bytes (a truncated file?)");
  const std::uint64_t values = std::uint64_t(l.frames) * std::uint64_t(l.points * 3 + l.analog_per_frame);
  check_memory(values * sizeof(double) * 2, b.source(), "reading the points and analog samples");
  return l;
}

double metres_per_c3d_unit(const std::string& units, const std::string& source) {
  const std::string u = lower(units);
  if (u.empty() || u == "mm") return 0.001;
  if (u == "cm") return 0.01;
  if (u == "m") return 1.0;
  if (u == "in") return 0.0254;
  if (u == "ft") return 0.3048;
  throw bad(source, "POINT:UNITS mm, cm, m, in or ft", escaped(units));
}

// The points that are markers (not listed in POINT:ANGLES, FORCES,
// MOMENTS, POWERS, SCALARS or REACTIONS: a model's outputs stored as
// points) and their names: the label without the subject's prefix
// (SUBJECTS:LABEL_PREFIXES, one subject), "*N" for a blank or missing
// label (N from 0), a repeated name suffixed "_2", "_3", ...
std::vector<int> marker_points(const C3dParams& p, long points, std::vector<std::string>& names) {
  const std::vector<std::string> labels = p.strings("POINT", "LABELS");
  std::set<std::string> computed;
  for (const char* list : {"ANGLES", "FORCES", "MOMENTS", "POWERS", "SCALARS", "REACTIONS"})
    for (const std::string& s : p.strings("POINT", list))
      if (!s.empty()) computed.insert(s);
  std::vector<std::string> prefixes;
  for (const std::string& s : p.strings("SUBJECTS", "LABEL_PREFIXES"))
    if (!s.empty()) prefixes.push_back(s);
  std::vector<int> kept;
  std::set<std::string> seen;
  for (long i = 0; i < points; ++i) {
    std::string name = std::size_t(i) < labels.size() ? labels[std::size_t(i)] : "";
    if (!name.empty() && computed.count(name)) continue;
    if (prefixes.size() == 1 && name.size() > prefixes[0].size() && name.rfind(prefixes[0], 0) == 0)
      name = name.substr(prefixes[0].size());
    if (name.empty()) name = "*" + std::to_string(i);
    std::string unique = name;
    for (int k = 2; !seen.insert(unique).second; ++k) unique = name + "_" + std::to_string(k);
    names.push_back(unique);
    kept.push_back(int(i));
  }
  return kept;
}

// A point is invalid (NaN) when its residual word is negative: a 16-bit
// integer below 0 or, stored as a float, a value below 0 or one whose 16-bit
// pattern is (65535 = -1, as some writers store it); also when its three
// coordinates are exactly 0 (older writers' mark) or not finite.
Trc read_points(const C3dBytes& b, const C3dParams& p, const Layout& l) {
  Trc trc;
  trc.source = b.source();
  trc.rate_hz = l.rate;
  trc.metres_per_unit = metres_per_c3d_unit(p.text("POINT", "UNITS"), b.source());
  const std::vector<int> kept = marker_points(p, l.points, trc.markers);
  trc.time_s.resize(std::size_t(l.frames));
  trc.xyz.assign(std::size_t(l.frames) * kept.size(), Eigen::Vector3d::Constant(kNaN));
  const bool floats = l.value_bytes == 4;
  for (long f = 0; f < l.frames; ++f) {
    trc.time_s[std::size_t(f)] = double(l.first - 1 + f) / l.rate;
    const std::size_t frame = l.data + std::size_t(f) * l.frame_bytes;
    for (std::size_t m = 0; m < kept.size(); ++m) {
      const std::size_t at = frame + std::size_t(kept[m]) * 4 * l.value_bytes;
      Eigen::Vector3d v;
      bool valid;
      if (floats) {
        for (int a = 0; a < 3; ++a) v[a] = b.f32(at + 4 * std::size_t(a), "a point coordinate");
        const double word = b.f32(at + 12, "a point residual");
        valid = word >= 0 && word < 32768;
      } else {
        for (int a = 0; a < 3; ++a) v[a] = b.i16(at + 2 * std::size_t(a), "a point coordinate") * l.scale;
        valid = b.i16(at + 6, "a point residual") >= 0;
      }
      if (valid && v.allFinite() && !v.isZero(0)) trc.xyz[std::size_t(f) * kept.size() + m] = v;
    }
  }
  return trc;
}

// (stored - OFFSET) x GEN_SCALE x SCALE per channel; 16-bit integers read
// unsigned (offsets too) when ANALOG:FORMAT is UNSIGNED. A missing SCALE or
// OFFSET entry is 1 or 0, a missing label "A<n>" (n from 1).
C3dAnalog read_analog(const C3dBytes& b, const C3dParams& p, const Layout& l) {
  C3dAnalog a;
  a.per_frame = int(l.per_frame);
  a.rate_hz = l.rate * double(l.per_frame);
  const double stated = p.number("ANALOG", "RATE", a.rate_hz);
  if (l.channels > 0 && std::abs(stated - a.rate_hz) > 1e-3 * a.rate_hz)
    throw bad(b.source(), "ANALOG:RATE " + number_text(a.rate_hz) + " Hz (" + std::to_string(l.per_frame) +
                              " samples per " + number_text(l.rate) + " Hz frame)",
              number_text(stated));
  a.labels = p.strings("ANALOG", "LABELS");
  a.units = p.strings("ANALOG", "UNITS");
  a.labels.resize(std::size_t(l.channels));
  a.units.resize(std::size_t(l.channels));
  for (std::size_t c = 0; c < a.labels.size(); ++c)
    if (a.labels[c].empty()) a.labels[c] = "A" + std::to_string(c + 1);
  std::vector<double> scale = p.numbers("ANALOG", "SCALE"), offset = p.numbers("ANALOG", "OFFSET");
  scale.resize(std::size_t(l.channels), 1.0);
  offset.resize(std::size_t(l.channels), 0.0);
  const double gen = p.number("ANALOG", "GEN_SCALE", 1.0);
  const bool floats = l.value_bytes == 4, is_unsigned = !floats && lower(p.text("ANALOG", "FORMAT")) == "unsigned";
  if (is_unsigned)
    for (double& o : offset) o = o < 0 ? o + 65536 : o;
  const std::size_t C = std::size_t(l.channels);
  a.values.resize(std::size_t(l.frames) * std::size_t(l.per_frame) * C);
  for (std::size_t s = 0; s < a.values.size() / std::max<std::size_t>(C, 1); ++s) {
    const std::size_t f = s / std::size_t(l.per_frame), k = s % std::size_t(l.per_frame);
    const std::size_t at = l.data + f * l.frame_bytes + (std::size_t(4 * l.points) + k * C) * l.value_bytes;
    for (std::size_t c = 0; c < C; ++c) {
      const std::size_t at_c = at + c * l.value_bytes;
      const double raw = floats ? b.f32(at_c, "an analog sample")
                         : is_unsigned ? double(b.u16(at_c, "an analog sample"))
                                       : double(b.i16(at_c, "an analog sample"));
      a.values[s * C + c] = (raw - offset[c]) * gen * scale[c];
    }
  }
  return a;
}

// The channels a plate of `type` reads (c3d.org, FORCE_PLATFORM:TYPE):
// 1: Fx Fy Fz Px Py Tz; 2 and 4: Fx Fy Fz Mx My Mz; 3: Fx12 Fx34 Fy14 Fy23
// Fz1 Fz2 Fz3 Fz4; other types: every row of CHANNEL.
int plate_channels(int type, int rows) { return type == 3 ? 8 : (type >= 1 && type <= 4) ? 6 : rows; }

// The FORCE_PLATFORM group; "" or why it cannot be used (its arrays too
// short for USED plates, a channel outside the analog channels).
std::string read_plates(const C3dParams& p, double metres, int channels, std::vector<C3dPlate>& plates) {
  const long used = p.count("FORCE_PLATFORM", "USED", 0);
  if (used <= 0) return "";
  const std::vector<double> type = p.numbers("FORCE_PLATFORM", "TYPE"), corners = p.numbers("FORCE_PLATFORM", "CORNERS"),
                            origin = p.numbers("FORCE_PLATFORM", "ORIGIN"), channel = p.numbers("FORCE_PLATFORM", "CHANNEL");
  const detail::C3dParam* channel_param = p.find("FORCE_PLATFORM", "CHANNEL");
  const detail::C3dParam* cal = p.find("FORCE_PLATFORM", "CAL_MATRIX");
  const long rows = channel_param && !channel_param->dims.empty() ? channel_param->dims[0] : 0;
  const std::string n = std::to_string(used) + " plates (FORCE_PLATFORM:USED)";
  if (long(type.size()) < used) return "FORCE_PLATFORM:TYPE holds " + std::to_string(type.size()) + " values for " + n;
  if (long(corners.size()) < 12 * used) return "FORCE_PLATFORM:CORNERS holds " + std::to_string(corners.size()) + " values for " + n;
  if (long(origin.size()) < 3 * used) return "FORCE_PLATFORM:ORIGIN holds " + std::to_string(origin.size()) + " values for " + n;
  if (rows == 0 || long(channel.size()) < rows * used)
    return "FORCE_PLATFORM:CHANNEL holds " + std::to_string(channel.size()) + " values for " + n;
  for (long i = 0; i < used; ++i) {
    C3dPlate plate;
    plate.type = int(std::clamp(whole(type[std::size_t(i)], 0), -1000L, 1000L));
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t a = 0; a < 3; ++a) plate.corners[k][long(a)] = corners[std::size_t(12 * i) + 3 * k + a] * metres;
    for (std::size_t a = 0; a < 3; ++a) plate.origin[long(a)] = origin[std::size_t(3 * i) + a] * metres;
    const int needed = plate_channels(plate.type, int(rows));
    if (needed > rows) return "FORCE_PLATFORM:CHANNEL has " + std::to_string(rows) + " rows, a type-" +
                              std::to_string(plate.type) + " plate needs " + std::to_string(needed);
    for (int k = 0; k < needed; ++k) {
      const double c = channel[std::size_t(i * rows + k)];
      if (!(c >= 1 && c <= channels))
        return "FORCE_PLATFORM:CHANNEL: plate " + std::to_string(i + 1) + " reads channel " + number_text(c) +
               " of the " + std::to_string(channels) + " analog channels";
      plate.channels.push_back(int(c) - 1);
    }
    if (cal && cal->dims.size() == 3 && cal->dims[0] == 6 && cal->dims[1] == 6 && cal->dims[2] > i &&
        long(cal->numbers.size()) >= 36 * (i + 1))
      plate.cal_matrix.assign(cal->numbers.begin() + 36 * i, cal->numbers.begin() + 36 * (i + 1));
    plates.push_back(std::move(plate));
  }
  return "";
}

std::string manufacturer(const C3dParams& p) {
  std::vector<std::string> parts;
  for (const char* name : {"COMPANY", "SOFTWARE", "VERSION_LABEL", "VERSION"}) {
    const std::string t = p.text("MANUFACTURER", name);
    if (!t.empty()) parts.push_back(t);
  }
  return join(parts, ", ");
}

}  // namespace

C3d parse_c3d(std::string_view bytes, const std::string& source) {
  std::size_t param_start = 0;
  const C3dFormat format = format_of(bytes, source, param_start);
  const C3dBytes b(bytes, format, source);
  const C3dParams p = C3dParams::parse(b, param_start);
  const Layout l = read_layout(b, p);
  C3d c;
  c.source = source;
  c.format = format;
  c.float_storage = l.value_bytes == 4;
  c.point_scale = l.scale;
  c.first_frame = int(l.first);
  c.units = p.text("POINT", "UNITS");
  c.points = read_points(b, p, l);
  c.analog = read_analog(b, p, l);
  c.plates_problem = read_plates(p, c.points.metres_per_unit, c.analog.channels(), c.plates);
  if (!c.plates_problem.empty()) c.plates.clear();
  const std::vector<double> zero = p.numbers("FORCE_PLATFORM", "ZERO");
  if (zero.size() >= 2 && zero[0] >= 1 && zero[1] >= zero[0] && zero[1] <= double(l.frames))
    c.plates_zero = {int(zero[0]), int(zero[1])};
  c.manufacturer = manufacturer(p);
  return c;
}

C3d read_c3d(const std::string& path) {
  note_input(path);
  return parse_c3d(read_file_bytes(path), path);  // binary, not text
}

bool is_c3d_path(const std::string& path) {
  return path.size() >= 4 && lower(path.substr(path.size() - 4)) == ".c3d";
}

Trc read_markers(const std::string& path) {
  return is_c3d_path(path) ? read_c3d(path).points : read_trc(path);
}

}  // namespace ptnet
