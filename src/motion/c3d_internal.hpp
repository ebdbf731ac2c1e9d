// Internal: the C3D reader's steps (see ptnet/c3d.hpp): the number formats,
// the parameter section, the reader on bytes in memory (tests, the fuzzer).
// Tests include it as "motion/c3d_internal.hpp".
//
// Dimension legend: V values of a parameter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ptnet/c3d.hpp"

namespace ptnet {

// read_c3d on the file's bytes; `source` names it in errors.
C3d parse_c3d(std::string_view bytes, const std::string& source);
// True for a path ending in .c3d (any case): load_motion reads its markers.
bool is_c3d_path(const std::string& path);

}  // namespace ptnet

namespace ptnet::detail {

inline constexpr std::size_t kC3dBlock = 512;  // bytes of a C3D block

// The file's bytes, read in its number format. Every read is bounds-checked:
// past the end is the Error "FILE: byte N: expected WHAT, found the end of
// the file".
class C3dBytes {
 public:
  C3dBytes(std::string_view bytes, C3dFormat format, std::string source)
      : bytes_(bytes), format_(format), source_(std::move(source)) {}
  std::size_t size() const { return bytes_.size(); }
  C3dFormat format() const { return format_; }
  const std::string& source() const { return source_; }
  // Throws unless bytes [at, at + n) are in the file.
  void need(std::size_t at, std::size_t n, const std::string& what) const;
  std::uint8_t u8(std::size_t at, const char* what) const;
  std::int8_t i8(std::size_t at, const char* what) const { return std::int8_t(u8(at, what)); }
  std::uint16_t u16(std::size_t at, const char* what) const;
  std::int16_t i16(std::size_t at, const char* what) const { return std::int16_t(u16(at, what)); }
  double f32(std::size_t at, const char* what) const;  // NaN for a DEC reserved operand
  std::string_view text(std::size_t at, std::size_t n, const char* what) const;

 private:
  std::string_view bytes_;
  C3dFormat format_;
  std::string source_;
};

// The value of 4 bytes in a number format (DEC: VAX F_floating).
double c3d_float(const unsigned char* b, C3dFormat format);

// One parameter: GROUP:NAME (upper case), its type (-1 characters, 1 byte,
// 2 16-bit integer, 4 float) and dimensions; numbers holds the values of a
// numeric parameter in storage order (16-bit integers as signed), strings
// those of a character one (the first dimension is the length; trailing
// blanks and NULs removed).
struct C3dParam {
  std::string group, name;
  int type = 0;
  std::vector<int> dims;
  std::vector<double> numbers;       // [V]
  std::vector<std::string> strings;  // [V]
};

class C3dParams {
 public:
  // The parameter section at byte `start` (its 4-byte header, then the
  // group and parameter records up to the section's blocks). A record that
  // does not fit the section is the Error "FILE: byte N: expected ...".
  static C3dParams parse(const C3dBytes& bytes, std::size_t start);
  const C3dParam* find(std::string_view group, std::string_view name) const;  // any case; null if absent
  // The values of GROUP:NAME and of its continuations NAME2, NAME3, ...
  // (c3d.org: arrays of more than 255 entries); empty when absent.
  std::vector<double> numbers(std::string_view group, std::string_view name) const;
  std::vector<std::string> strings(std::string_view group, std::string_view name) const;
  // The first value of a numeric parameter; `fallback` when absent or empty.
  double number(std::string_view group, std::string_view name, double fallback) const;
  // A count (USED, FRAMES, DATA_START): 16-bit integers read unsigned.
  long count(std::string_view group, std::string_view name, long fallback) const;
  std::string text(std::string_view group, std::string_view name) const;  // the strings joined by ' '
  std::size_t blocks() const { return blocks_; }

 private:
  std::vector<C3dParam> params_;
  std::size_t blocks_ = 0;
};

}  // namespace ptnet::detail
