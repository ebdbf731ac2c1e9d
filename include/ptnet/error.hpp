// ptnet/error.hpp: the project's one error type.
//
//   throw ptnet::Error::at("walk.bvh", 42, "CHANNELS", "OFFSET");
//   // what(): "walk.bvh:42: expected CHANNELS, found OFFSET"
//   throw ptnet::Error::in("a.h5", "exists; pass " + ptnet::field_text("force") + " to overwrite",
//                          ptnet::ErrorKind::exists);
//   // what(): "a.h5: exists; pass force to overwrite"
//   // the CLI: "a.h5: exists; pass --force to overwrite"
//
// Every failure a user can cause (bad file, bad argument, impossible
// attribute) is a ptnet::Error whose what() is one line naming the file and
// the problem. main() prints it on stderr and exits with status 1; the
// Python module raises the exception its kind() names.
//
// A message names an option by its field in the library's structs
// (TrainOptions::micro_batch: "micro_batch"), never by a command-line flag,
// and writes it with field_text(): what() shows the field's name, while a
// front end shows its own spelling through Error::text (the CLI its flag,
// "--micro-batch": app/ptnet.cpp).
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ptnet {

// What went wrong, for callers that react by kind (the Python module raises
// the exception in brackets).
enum class ErrorKind {
  invalid,    // an argument or option value the call cannot use  (ValueError)
  format,     // a file whose content is not what it should be     (ValueError)
  not_found,  // a file or folder that is not there                (FileNotFoundError)
  exists,     // an output that exists while force is off          (FileExistsError)
  io,         // a file or folder that cannot be opened, read, written or created (OSError)
};

namespace detail {
constexpr char kFieldMark = '\x1f';  // around a field's name in a message
// `marked` with each field_text(name) replaced by spell(name).
template <class Spell>
std::string spell_fields(std::string_view marked, const Spell& spell) {
  const auto field_char = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  };
  std::string out;
  for (std::size_t i = 0; i < marked.size();) {
    if (marked[i] == kFieldMark) {
      std::size_t end = i + 1;
      while (end < marked.size() && field_char(marked[end])) ++end;
      if (end > i + 1 && end < marked.size() && marked[end] == kFieldMark) {
        out += spell(marked.substr(i + 1, end - i - 1));
        i = end + 1;
        continue;
      }
    }
    out += marked[i++];
  }
  return out;
}
inline std::string_view own_name(std::string_view field) { return field; }
}  // namespace detail

// An option field in a message ("force", "micro_batch": lower case, digits
// and '_'), as the library's structs spell it.
inline std::string field_text(std::string_view field) {
  return detail::kFieldMark + std::string(field) + detail::kFieldMark;
}

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, ErrorKind kind = ErrorKind::invalid)
      : std::runtime_error(detail::spell_fields(message, detail::own_name)),
        marked_(message.find(detail::kFieldMark) == std::string::npos
                    ? nullptr
                    : std::make_shared<const std::string>(message)),
        kind_(kind) {}

  // "FILE:LINE: expected X, found Y" (the parser style).
  static Error at(const std::string& file, long line, const std::string& expected,
                  const std::string& found) {
    return Error(file + ":" + std::to_string(line) + ": expected " + expected + ", found " + found,
                 ErrorKind::format);
  }
  // "FILE: PROBLEM" (whole-file problems: missing, unreadable, wrong format).
  static Error in(const std::string& file, const std::string& problem,
                  ErrorKind kind = ErrorKind::format) {
    return Error(file + ": " + problem, kind);
  }

  ErrorKind kind() const noexcept { return kind_; }
  // The message with its option fields spelled by `spell` (a callable
  // string_view -> string): what() is text() with each field's own name.
  template <class Spell>
  std::string text(const Spell& spell) const {
    return marked_ ? detail::spell_fields(*marked_, spell) : std::string(what());
  }
  // The message with its fields still marked: an Error that rewords this one
  // keeps them, and its kind (Error("where: " + e.message(), e.kind())).
  std::string message() const { return marked_ ? *marked_ : std::string(what()); }

 private:
  std::shared_ptr<const std::string> marked_;  // the message with field marks; null without fields
  ErrorKind kind_;
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

// A number for a message: whole numbers below 1e15 in full ("1048576"), others
// to at most 6 significant digits ("0.15", "1e+308", "nan").
inline std::string number_text(double v) {
  char buf[32];
  if (std::abs(v) < 1e15 && v == std::trunc(v))
    std::snprintf(buf, sizeof buf, "%.0f", v);  // whole numbers in full: 1048576, not 1.04858e+06
  else
    std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// A number to as many significant digits as tell it apart from its
// neighbours (6 to 17: "120", "120.0005", "59.998800023999518"), for a
// message comparing numbers that number_text would print alike.
inline std::string precise_text(double v) {
  char buf[40];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

// The values an option accepts: finite numbers in [lo, hi] ((lo, hi] with
// lo_open). Declared once beside the option (SimSettings::kRanges,
// TrainOptions's ranges) and read by the library's check (check_range) and by
// a front end's own validator (the CLI's in_range), so the two never differ.
struct Range {
  double lo = 0, hi = 0;
  bool lo_open = false;
  bool contains(double v) const { return std::isfinite(v) && v >= lo && v <= hi && !(lo_open && v == lo); }
  // "[0, 0.24]", "(0, 10]"
  std::string text() const { return std::string(lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + "]"; }
};

// Throws Error "FIELD: V is not in [lo, hi]" (the field as field_text) when
// `value` is outside `range`.
inline void check_range(std::string_view field, double value, const Range& range) {
  if (!range.contains(value))
    throw Error(field_text(field) + ": " + number_text(value) + " is not in " + range.text());
}

}  // namespace ptnet
