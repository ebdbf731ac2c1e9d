// ptnet: the command-line tool. Thin glue: each subcommand lives in
// app/cmd_<name>.cpp and calls the library's public headers.
//
// Two executables are built from these files (app/CMakeLists.txt):
//   ptnet        the commands that need no LibTorch (simulate, bodies, info,
//                render, forces, merge, motions, physics-bench); for any other command line it
//                runs ptnet-torch with the same arguments (execv).
//   ptnet-torch  every command, linked with LibTorch: beside ptnet in the
//                build folder, in libexec/ptnet/ when installed.
// Loading LibTorch's shared libraries costs ~0.5 CPU s at every start; the
// split keeps that off the commands that do not use it (docs/simulate.md).
//
// Exit codes: 0 ok, 1 bad input or runtime error, 2 usage error.
#if PTNET_WITH_TORCH
#include <c10/util/Exception.h>
#endif
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "command.hpp"
#include "local_ranks.hpp"
#include "ptnet/error.hpp"
#include "ptnet/memory.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::cli {
Globals& globals() {
  static Globals g;
  return g;
}
}  // namespace ptnet::cli

namespace {

// The command line's first argument that is not the global flag `quiet`
// (-q, --quiet): the subcommand, an option (--help, --version) or empty.
std::string first_word(const CLI::Option& quiet, int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (!quiet.check_name(argv[i])) return argv[i];
  return std::string();
}

// The flag that sets an option field a library message names (ptnet/error.hpp,
// field_text) in `command`: "micro_batch" -> "--micro-batch", but for the
// flags named otherwise than their field.
std::string flag_of(const std::string& command, std::string_view field) {
  struct Renamed {
    std::string_view command, field, flag;  // command "": every command
  };
  static constexpr Renamed kRenamed[] = {
      {"", "dist_timeout_s", "--dist-timeout"},
      {"train", "dist_token", ptnet::cli::kDistTokenVariable},  // an environment variable
      {"evaluate", "threshold_kpa", "--threshold"},
      {"simulate", "pitch_m", "--pitch"},
      {"simulate", "forces_dir", "--forces"},
      {"render", "sequences", "--sequence"},
      {"forces", "contact_kpa", "--contact"},
      {"physics-bench", "units", "the trials CSV's units column"},
  };
  for (const Renamed& r : kRenamed)
    if (r.field == field && (r.command.empty() || r.command == command)) return std::string(r.flag);
  std::string flag = "--";
  for (char c : field) flag += c == '_' ? '-' : c;
  return flag;
}

// An Error as the command line says it: option fields as flags.
std::string cli_text(const ptnet::Error& e, const CLI::App& app) {
  const std::vector<CLI::App*> run = app.get_subcommands();
  const std::string command = run.empty() ? std::string() : run.front()->get_name();
  return ptnet::one_line(e.text([&](std::string_view field) { return flag_of(command, field); }));
}

bool is_command(const CLI::App& app, const std::string& word) {
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->get_name() == word) return true;
  return false;
}

#if !PTNET_WITH_TORCH
// Replaces this process with ptnet-torch on the same arguments: the one
// beside this executable (the build folder) or, installed, the one at
// PTNET_TORCH_FROM_BINDIR from this executable's folder (bin/ ->
// libexec/ptnet/, cmake/install.cmake). Returns only on failure, with the
// exit status.
int run_torch_executable(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    std::cerr << "ptnet: error: /proc/self/exe: cannot read this executable's path (" << ec.message() << ")\n";
    return 1;
  }
  const fs::path beside = self.parent_path() / "ptnet-torch";
  const fs::path installed = (self.parent_path() / PTNET_TORCH_FROM_BINDIR).lexically_normal();
  const fs::path& torch_exe = fs::exists(beside, ec) || !fs::exists(installed, ec) ? beside : installed;
  // OpenMP threads waiting for each other spin before they sleep (libgomp: up
  // to 300,000 pauses, milliseconds): beside other work, two training threads
  // ran an epoch 6x slower than one; sleeping at once they stay faster than
  // one, for 14-19 % on an idle machine (docs/model.md, "Threads"). The same
  // results either way; the user's own setting wins.
  if (!std::getenv("OMP_WAIT_POLICY") && !std::getenv("GOMP_SPINCOUNT")) ::setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
  std::vector<char*> args(argv, argv + argc);
  args.push_back(nullptr);
  ::execv(torch_exe.c_str(), args.data());
  if (errno == ENOENT)
    std::cerr << "ptnet: error: ptnet-torch: found neither " << beside.string() << " nor " << installed.string()
              << "; the model commands live there: build it (make build) or reinstall ptnet\n";
  else
    std::cerr << "ptnet: error: " << torch_exe.string() << ": cannot run it (" << std::strerror(errno) << ")\n";
  return 1;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  ptnet::keep_freed_memory();  // ptnet/memory.hpp: no page faults for freed and retaken tensors
  CLI::App app{
      "ptnet: PressureTransferNet. Simulates 80 x 28 ground-pressure-mat recordings from motion\n"
      "capture retargeted onto bodies of any sex, height and weight, and trains and runs an\n"
      "encoder-decoder that transfers a pressure sequence from one body to another.",
      "ptnet"};
  app.set_version_flag("--version", std::string("ptnet ") + PTNET_VERSION);
  app.require_subcommand(1);
  const CLI::Option* quiet = app.add_flag("-q,--quiet", ptnet::cli::globals().quiet, "No progress messages on stderr");
  app.fallthrough();

  auto commands = ptnet::cli::registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [order, setup] : commands) setup(app);
  // Arguments are text too (paths and names that outputs record, and that
  // JSON and HDF5 hold as UTF-8): refused in one line before any work.
  for (int i = 1; i < argc; ++i)
    if (ptnet::utf8_invalid_at(argv[i]) != std::string::npos) {
      std::cerr << "ptnet: error: argument " << ptnet::escaped(argv[i], 60)
                << " is not UTF-8 (ptnet reads names and paths as UTF-8: rename the file)\n";
      return 2;
    }
  const std::string word = first_word(*quiet, argc, argv);
#if !PTNET_WITH_TORCH
  // Not one of this executable's commands (or --help, --version): ptnet-torch
  // answers, with every command.
  if (!is_command(app, word)) return run_torch_executable(argc, argv);
#endif
  if (!word.empty() && word[0] != '-' && !is_command(app, word)) {
    std::cerr << "ptnet: error: " << ptnet::escaped(word, 40) << ": not a command (ptnet --help)\n";
    return 2;
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // usage: one line, status 2
    std::cerr << "ptnet: error: " << ptnet::one_line(e.what()) << " (ptnet --help)\n";
    return 2;
  } catch (const ptnet::Error& e) {
    std::cerr << "ptnet: error: " << cli_text(e, app) << "\n";
    return 1;
#if PTNET_WITH_TORCH
  } catch (const c10::Error& e) {
    std::cerr << "ptnet: error: " << ptnet::one_line(e.what_without_backtrace()) << "\n";
    return 1;
#endif
  } catch (const std::bad_alloc&) {
    std::cerr << "ptnet: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "ptnet: error: " << ptnet::one_line(e.what()) << "\n";
    return 1;
  }
  return 0;
}
