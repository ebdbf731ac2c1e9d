// cli_test_util.hpp: running the real ptnet binary (PTNET_BINARY) from the
// smoke tests, with its exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ptnet::testing_cli {

struct RunResult {
  int status = -1;       // exit status (128 + signal if killed)
  std::string out, err;  // stdout, stderr
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `ENV EXE ARGS` (in folder `cwd` if given; `env`: variable
// assignments or empty), capturing its output through two scratch files
// `scratch`.out / `scratch`.err, removed afterwards.
inline RunResult run_program(const std::filesystem::path& exe, const std::string& args,
                             const std::filesystem::path& scratch, const std::filesystem::path& cwd = {},
                             const std::string& env = "") {
  const std::filesystem::path out = scratch.string() + ".out", err = scratch.string() + ".err";
  const std::string cd = cwd.empty() ? "" : "cd '" + cwd.string() + "' && ";
  const std::string cmd = cd + env + " '" + exe.string() + "' " + args + " >'" + out.string() + "' 2>'" +
                          err.string() + "'";
  const int raw = std::system(cmd.c_str());
  RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// Runs `ptnet ARGS` (PTNET_BINARY), as run_program.
inline RunResult run_ptnet(const std::string& args, const std::filesystem::path& scratch,
                           const std::filesystem::path& cwd = {}) {
  return run_program(PTNET_BINARY, args, scratch, cwd);
}

}  // namespace ptnet::testing_cli
