// app/command.hpp: how a subcommand joins the ptnet tool.
//
// Each app/cmd_<name>.cpp defines `void setup(CLI::App& app)` that adds its
// subcommand (options bound to an options struct, a callback that runs it) and
// registers it with PTNET_COMMAND(order, setup). main() adds them in order.
#pragma once

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/parallel.hpp"

namespace ptnet::cli {

using Setup = void (*)(CLI::App& app);

inline std::vector<std::pair<int, Setup>>& registry() {
  static std::vector<std::pair<int, Setup>> commands;
  return commands;
}

struct Registrar {
  Registrar(int order, Setup setup) { registry().emplace_back(order, setup); }
};

// ---- Option checks. Every numeric option has one: a range that NaN and Inf
// fall outside of, and messages with short numbers ("--lr: 0 is not in
// (0, 10]").

// A finite number in [lo, hi] (lo_open: (lo, hi]).
inline CLI::Validator in_range(double lo, double hi, bool lo_open = false) {
  const std::string range = std::string(lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + "]";
  return CLI::Validator(
      [=](std::string& input) -> std::string {
        double v = 0;
        std::size_t used = 0;
        try {
          v = std::stod(input, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != input.size()) return escaped(input, 30) + " is not a number";
        if (!std::isfinite(v) || v < lo || v > hi || (lo_open && v == lo))
          return escaped(input, 30) + " is not in " + range;
        return std::string();
      },
      "in " + range);
}
// A number > 0 (and <= hi).
inline CLI::Validator positive(double hi = 1e9) { return in_range(0, hi, /*lo_open=*/true); }
// Threads: 1 .. max_threads() (0 too when it means "the default").
inline CLI::Validator thread_count(bool zero_means_default) {
  return in_range(zero_means_default ? 0 : 1, max_threads());
}

// Global flags every command may read (set by main before callbacks run).
struct Globals {
  bool quiet = false;  // no progress on stderr
};
Globals& globals();

// Progress of long work on stderr ("evaluate: 40/480 pairs"): one updating
// line on a terminal, a line per 10 % in a log, nothing with --quiet.
inline void print_progress(const std::string& what, int done, int total, const std::string& unit) {
  if (globals().quiet) return;
  static const bool tty = ::isatty(2) != 0;
  const int step = std::max(1, total / (tty ? 100 : 10));
  if (done % step == 0 || done == total)
    std::cerr << what << ": " << done << "/" << total << " " << unit << (done == total || !tty ? "\n" : "\r")
              << std::flush;
}

}  // namespace ptnet::cli

#define PTNET_CONCAT_(a, b) a##b
#define PTNET_CONCAT(a, b) PTNET_CONCAT_(a, b)
#define PTNET_COMMAND(order, setup) \
  static const ::ptnet::cli::Registrar PTNET_CONCAT(ptnet_command_, __LINE__)(order, setup)
