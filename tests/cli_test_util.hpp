// cli_test_util.hpp: running the real ptnet binary (PTNET_BINARY) from the
// smoke tests, with its exit status, stdout and stderr; in the background,
// with a bounded wait.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

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

// `ptnet ARGS` in the background (environment `env`: assignments or
// empty), its stderr into `err`, its stdout into `out` (or discarded). The
// pid is ptnet's own (the shell execs it).
inline pid_t spawn_ptnet(const std::string& args, const std::filesystem::path& err, const std::string& env = "",
                         const std::filesystem::path& out = "/dev/null") {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string cmd = "exec env " + env + " '" + std::string(PTNET_BINARY) + "' " + args + " 2>'" +
                            err.string() + "' >'" + out.string() + "'";
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

// The exit status of a process started by spawn_ptnet (128 + signal if
// killed), waiting as long as it takes.
inline int wait_status(pid_t pid) {
  int raw = 0;
  ::waitpid(pid, &raw, 0);
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
}

// The same, waiting at most `seconds`: a process still running then is
// killed (SIGKILL) and -1 returned. `max_rss_kb`: its peak resident memory.
inline int wait_within(pid_t pid, double seconds, long* max_rss_kb = nullptr) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int raw = 0;
  rusage usage{};
  for (;;) {
    const pid_t got = ::wait4(pid, &raw, WNOHANG, &usage);
    if (got == pid) break;
    if (got < 0) return -1;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::wait4(pid, &raw, 0, &usage);
      if (max_rss_kb) *max_rss_kb = usage.ru_maxrss;
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  if (max_rss_kb) *max_rss_kb = usage.ru_maxrss;
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
}

}  // namespace ptnet::testing_cli
