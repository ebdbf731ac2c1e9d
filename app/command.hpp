// app/command.hpp: how a subcommand joins the ptnet tool.
//
// Each app/cmd_<name>.cpp defines `void setup(CLI::App& app)` that adds its
// subcommand (options bound to an options struct, a callback that runs it) and
// registers it with PTNET_COMMAND(order, setup). main() adds them in order.
#pragma once

#include <CLI/CLI.hpp>
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

}  // namespace ptnet::cli

#define PTNET_CONCAT_(a, b) a##b
#define PTNET_CONCAT(a, b) PTNET_CONCAT_(a, b)
#define PTNET_COMMAND(order, setup) \
  static const ::ptnet::cli::Registrar PTNET_CONCAT(ptnet_command_, __LINE__)(order, setup)
