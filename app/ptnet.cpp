// ptnet: the command-line tool. Thin glue: each subcommand lives in
// app/cmd_<name>.cpp and calls the library's public headers.
//
// Exit codes: 0 ok, 1 bad input or runtime error, 2 usage error.
#include <c10/util/Exception.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "command.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::cli {
Globals& globals() {
  static Globals g;
  return g;
}
}  // namespace ptnet::cli

int main(int argc, char** argv) {
  CLI::App app{
      "ptnet: PressureTransferNet. Simulates 80 x 28 ground-pressure-mat recordings from motion\n"
      "capture retargeted onto bodies of any sex, height and weight, and trains and runs an\n"
      "encoder-decoder that transfers a pressure sequence from one body to another.",
      "ptnet"};
  app.set_version_flag("--version", std::string("ptnet ") + PTNET_VERSION);
  app.require_subcommand(1);
  app.add_flag("-q,--quiet", ptnet::cli::globals().quiet, "No progress messages on stderr");
  app.fallthrough();

  auto commands = ptnet::cli::registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [order, setup] : commands) setup(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // usage: one line, status 2
    std::cerr << "ptnet: error: " << ptnet::one_line(e.what()) << " (ptnet --help)\n";
    return 2;
  } catch (const ptnet::Error& e) {
    std::cerr << "ptnet: error: " << ptnet::one_line(e.what()) << "\n";
    return 1;
  } catch (const c10::Error& e) {
    std::cerr << "ptnet: error: " << ptnet::one_line(e.what_without_backtrace()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "ptnet: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "ptnet: error: " << ptnet::one_line(e.what()) << "\n";
    return 1;
  }
  return 0;
}
