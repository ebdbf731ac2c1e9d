// ptnet/error.hpp: the project's one error type.
//
//   throw ptnet::Error::at("walk.bvh", 42, "CHANNELS", "OFFSET");
//   // what(): "walk.bvh:42: expected CHANNELS, found OFFSET"
//
// Every failure a user can cause (bad file, bad argument, impossible
// attribute) is a ptnet::Error whose what() is one line naming the file and
// the problem. main() prints it on stderr and exits with status 1.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ptnet {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}

  // "FILE:LINE: expected X, found Y" (the parser style).
  static Error at(const std::string& file, long line, const std::string& expected,
                  const std::string& found) {
    return Error(file + ":" + std::to_string(line) + ": expected " + expected + ", found " +
                 found);
  }
  // "FILE: PROBLEM" (whole-file problems: missing, unreadable, wrong format).
  static Error in(const std::string& file, const std::string& problem) {
    return Error(file + ": " + problem);
  }
};

// File content for a message: control and non-ASCII bytes escaped (\x1b),
// cut to `max` characters with "...", in single quotes (unless `quotes` is
// false). Use it for every piece of a file echoed in an error.
inline std::string escaped(std::string_view text, std::size_t max = 40, bool quotes = true) {
  std::string out = quotes ? "'" : "";
  std::size_t shown = 0;
  for (unsigned char c : text) {
    if (shown >= max) {
      out += "...";
      break;
    }
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += char(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
    ++shown;
  }
  return quotes ? out + "'" : out;
}

// A number with `digits` decimals ("1.290"): tables and reports.
inline std::string fixed_text(double v, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// A number for a message: at most 6 significant digits ("1e+308", "nan").
inline std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace ptnet
