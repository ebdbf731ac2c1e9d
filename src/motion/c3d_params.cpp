// C3D number formats and the parameter section (c3d.org, "The C3D File
// Format User Guide": "The parameter section", "Processor type"): a 4-byte
// header (the section's block count, the processor type), then group and
// parameter records, each pointing at the next; a record with a zero-length
// name, or a zero pointer, ends the section.
#include <cmath>
#include <cstring>
#include <limits>

#include "motion/c3d_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

const char* c3d_format_name(C3dFormat format) {
  switch (format) {
    case C3dFormat::intel: return "Intel";
    case C3dFormat::dec: return "DEC";
    case C3dFormat::mips: return "MIPS";
  }
  return "?";
}

namespace detail {

double c3d_float(const unsigned char* b, C3dFormat format) {
  if (format == C3dFormat::dec) {
    // VAX F_floating: two little-endian 16-bit words, the first holding the
    // sign, the 8-bit exponent (excess 128) and the fraction's top 7 bits;
    // value = 0.1fff... (binary) x 2^(e - 128). e = 0: zero, or with the
    // sign set a reserved operand.
    const std::uint32_t w = std::uint32_t(b[0]) << 16 | std::uint32_t(b[1]) << 24 | b[2] | std::uint32_t(b[3]) << 8;
    const int e = int(w >> 23 & 0xff);
    if (e == 0) return (w >> 31) ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    const double v = std::ldexp(1.0 + double(w & 0x7fffff) / double(1 << 23), e - 129);
    return (w >> 31) ? -v : v;
  }
  std::uint32_t w = format == C3dFormat::mips
                        ? std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3]
                        : std::uint32_t(b[3]) << 24 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[1]) << 8 | b[0];
  float f;
  std::memcpy(&f, &w, sizeof f);
  return double(f);
}

void C3dBytes::need(std::size_t at, std::size_t n, const std::string& what) const {
  if (at > bytes_.size() || n > bytes_.size() - at)
    throw Error::in(source_, "byte " + std::to_string(at) + ": expected " + what + ", found the end of the file (" +
                                 std::to_string(bytes_.size()) + " bytes)");
}

std::uint8_t C3dBytes::u8(std::size_t at, const char* what) const {
  need(at, 1, what);
  return std::uint8_t(bytes_[at]);
}

std::uint16_t C3dBytes::u16(std::size_t at, const char* what) const {
  need(at, 2, what);
  const auto* b = reinterpret_cast<const unsigned char*>(bytes_.data() + at);
  return format_ == C3dFormat::mips ? std::uint16_t(b[0] << 8 | b[1]) : std::uint16_t(b[1] << 8 | b[0]);
}

double C3dBytes::f32(std::size_t at, const char* what) const {
  need(at, 4, what);
  return c3d_float(reinterpret_cast<const unsigned char*>(bytes_.data() + at), format_);
}

std::string_view C3dBytes::text(std::size_t at, std::size_t n, const char* what) const {
  need(at, n, what);
  return bytes_.substr(at, n);
}

namespace {

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string trimmed(std::string_view s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.remove_suffix(1);
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  return std::string(s);
}

// A string parameter as UTF-8: as it is when it is UTF-8 (ASCII, as c3d.org
// has them), else read as Latin-1 (ISO 8859-1), the 8-bit text of the
// writers that store "mm/s\xb2" or "Genou_\xe9": each byte its code point.
std::string utf8_text(std::string s) {
  if (utf8_invalid_at(s) == std::string::npos) return s;
  std::string out;
  for (unsigned char c : s)
    if (c < 0x80) {
      out += char(c);
    } else {
      out += char(0xC0 | (c >> 6));
      out += char(0x80 | (c & 0x3F));
    }
  return out;
}

// The type, dimensions and values of a parameter record whose type byte is
// at `at`; the values must end by `end` (the next record).
void read_values(const C3dBytes& b, std::size_t at, std::size_t end, C3dParam& p) {
  const std::string where = "parameter " + p.group + ":" + p.name;
  p.type = b.i8(at, "a parameter type");
  if (p.type != -1 && p.type != 1 && p.type != 2 && p.type != 4)
    throw Error::in(b.source(), "byte " + std::to_string(at) + ": expected the type of " + where +
                                    " (-1, 1, 2 or 4), found " + std::to_string(p.type));
  const int n_dims = b.u8(at + 1, "a parameter's dimension count");
  if (n_dims > 7)
    throw Error::in(b.source(), "byte " + std::to_string(at + 1) + ": expected at most 7 dimensions of " + where +
                                    ", found " + std::to_string(n_dims));
  std::uint64_t count = 1;
  for (int d = 0; d < n_dims; ++d) {
    p.dims.push_back(b.u8(at + 2 + std::size_t(d), "a parameter dimension"));
    count *= std::uint64_t(p.dims.back());  // <= 255^7: no overflow
  }
  const std::size_t data = at + 2 + std::size_t(n_dims);
  const std::uint64_t bytes = count * std::uint64_t(std::abs(p.type));
  if (data > end || bytes > end - data)
    throw Error::in(b.source(), "byte " + std::to_string(data) + ": expected the " + std::to_string(bytes) +
                                    " bytes of " + where + " before the next record at byte " + std::to_string(end) +
                                    " (a bad parameter section)");
  const std::size_t n = std::size_t(count);
  if (p.type == -1) {
    const std::size_t len = n_dims == 0 ? 1 : std::size_t(p.dims[0]);
    const std::size_t strings = len == 0 ? 0 : n / len;
    for (std::size_t i = 0; i < strings; ++i) p.strings.push_back(utf8_text(trimmed(b.text(data + i * len, len, "a string"))));
    return;
  }
  p.numbers.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t at_i = data + i * std::size_t(std::abs(p.type));
    p.numbers.push_back(p.type == 1 ? double(b.u8(at_i, "a byte"))
                        : p.type == 2 ? double(b.i16(at_i, "an integer"))
                                      : b.f32(at_i, "a float"));
  }
}

}  // namespace

C3dParams C3dParams::parse(const C3dBytes& b, std::size_t start) {
  C3dParams out;
  out.blocks_ = b.u8(start + 2, "the parameter section's block count");
  if (out.blocks_ == 0)
    throw Error::in(b.source(), "byte " + std::to_string(start + 2) +
                                    ": expected the parameter section's block count, found 0");
  const std::size_t end = std::min(b.size(), start + out.blocks_ * kC3dBlock);
  std::vector<std::pair<int, std::string>> groups;  // id, name
  std::vector<int> group_of;                        // per parameter
  for (std::size_t at = start + 4; at + 2 <= end;) {
    const int name_len = std::abs(int(b.i8(at, "a parameter name's length")));
    const int id = b.i8(at + 1, "a group id");
    if (name_len == 0) break;
    const std::string name = upper(b.text(at + 2, std::size_t(name_len), "a parameter name"));
    const std::size_t link = at + 2 + std::size_t(name_len);
    const int offset = b.i16(link, "the offset of the next record");
    if (offset < 0 || link + std::size_t(offset) > end)
      throw Error::in(b.source(), "byte " + std::to_string(link) + ": expected the offset of the record after " +
                                      escaped(name) + " inside the parameter section (bytes " +
                                      std::to_string(start) + "-" + std::to_string(end) + "), found " +
                                      std::to_string(offset) + " (a bad parameter section)");
    const std::size_t next = offset == 0 ? end : link + std::size_t(offset);
    if (id == 0)
      throw Error::in(b.source(), "byte " + std::to_string(at + 1) + ": expected a group id of " + escaped(name) +
                                      ", found 0 (a bad parameter section)");
    if (id < 0) {
      groups.emplace_back(-id, name);
    } else {
      C3dParam p;
      p.name = name;
      p.group = "group " + std::to_string(id);  // for messages, until the groups are known
      for (const auto& [gid, gname] : groups)
        if (gid == id) p.group = gname;
      read_values(b, link + 2, next, p);
      out.params_.push_back(std::move(p));
      group_of.push_back(id);
    }
    if (offset == 0) break;
    at = next;
  }
  for (std::size_t i = 0; i < out.params_.size(); ++i) {
    out.params_[i].group.clear();  // a group never defined: no GROUP:NAME finds it
    for (const auto& [id, name] : groups)
      if (id == group_of[i]) out.params_[i].group = name;
  }
  return out;
}

const C3dParam* C3dParams::find(std::string_view group, std::string_view name) const {
  const std::string g = upper(group), n = upper(name);
  for (const C3dParam& p : params_)
    if (p.group == g && p.name == n) return &p;
  return nullptr;
}

std::vector<double> C3dParams::numbers(std::string_view group, std::string_view name) const {
  std::vector<double> out;
  for (int k = 1;; ++k) {
    const C3dParam* p = find(group, k == 1 ? std::string(name) : std::string(name) + std::to_string(k));
    if (!p) return out;
    out.insert(out.end(), p->numbers.begin(), p->numbers.end());
  }
}

std::vector<std::string> C3dParams::strings(std::string_view group, std::string_view name) const {
  std::vector<std::string> out;
  for (int k = 1;; ++k) {
    const C3dParam* p = find(group, k == 1 ? std::string(name) : std::string(name) + std::to_string(k));
    if (!p) return out;
    out.insert(out.end(), p->strings.begin(), p->strings.end());
  }
}

double C3dParams::number(std::string_view group, std::string_view name, double fallback) const {
  const C3dParam* p = find(group, name);
  return p && !p->numbers.empty() ? p->numbers[0] : fallback;
}

long C3dParams::count(std::string_view group, std::string_view name, long fallback) const {
  const C3dParam* p = find(group, name);
  if (!p || p->numbers.empty()) return fallback;
  const double v = p->numbers[0];
  if (p->type == 2 && v < 0) return long(v) + 65536;  // counts are unsigned 16-bit
  return std::isfinite(v) && v >= 0 && v < 4e9 ? long(v) : -1;
}

std::string C3dParams::text(std::string_view group, std::string_view name) const {
  const C3dParam* p = find(group, name);
  if (!p) return "";
  if (p->type != -1) {
    std::vector<std::string> v;
    for (double x : p->numbers) v.push_back(number_text(x));
    return join(v, ".");
  }
  std::vector<std::string> v;
  for (const std::string& s : p->strings)
    if (!s.empty()) v.push_back(s);
  return join(v, " ");
}

}  // namespace detail
}  // namespace ptnet
