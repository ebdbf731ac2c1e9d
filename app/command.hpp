// app/command.hpp: how a subcommand joins the ptnet tool.
//
// Each app/cmd_<name>.cpp defines `void setup(CLI::App& app)` that adds its
// subcommand (options bound to an options struct, a callback that runs it) and
// registers it with PTNET_COMMAND(order, setup). main() adds them in order.
#pragma once

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace ptnet::cli {

using Setup = void (*)(CLI::App& app);

inline std::vector<std::pair<int, Setup>>& registry() {
  static std::vector<std::pair<int, Setup>> commands;
  return commands;
}

struct Registrar {
  Registrar(int order, Setup setup) { registry().emplace_back(order, setup); }
};

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
