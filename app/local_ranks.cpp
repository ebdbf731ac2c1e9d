// `ptnet train --nproc N`: N local ranks on 127.0.0.1 (see local_ranks.hpp).
#include "local_ranks.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/random.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet::cli {
namespace {

constexpr int kMaxRanks = 256;
std::array<std::atomic<pid_t>, kMaxRanks> g_children{};  // read by the signal handler
std::atomic<int> g_signal{0};

// Sends `sig` to every running rank; a stopped one (SIGSTOP, Ctrl-Z) is
// continued so that it can act on it.
void signal_ranks(int sig) {
  for (auto& pid : g_children)
    if (pid_t p = pid.load(); p > 0) {
      ::kill(p, sig);
      ::kill(p, SIGCONT);
    }
}

// Ctrl-C (SIGINT, SIGTERM, SIGHUP) of the launcher: the ranks stop, then the
// launcher dies of the same signal. Only the launcher's own signals come
// here: those it sends its ranks (signal_ranks) are not recorded.
extern "C" void forward_signal(int sig) {
  g_signal.store(sig);
  signal_ranks(SIGTERM);
}

// A TCP port free on 127.0.0.1 now (the kernel's choice); rank 0's store
// binds it a moment later.
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw Error("train --nproc: cannot open a socket to find a free port");
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 &&
                  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0;
  ::close(fd);
  if (!ok) throw Error("train --nproc: no free TCP port on 127.0.0.1");
  return ntohs(addr.sin_port);
}

// A run's token: 16 random bytes (the kernel's), in hex.
std::string random_token() {
  unsigned char bytes[16];
  if (::getrandom(bytes, sizeof bytes, 0) != ssize_t(sizeof bytes))
    throw Error("train --nproc: no random bytes for the run's token (getrandom: " + std::string(::strerror(errno)) +
                ")");
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned char b : bytes) hex += {kHex[b >> 4], kHex[b & 15]};
  return hex;
}

// This process's command line, without `--nproc N` / `--nproc=N`.
std::vector<std::string> own_arguments() {
  const std::string raw = read_file_bytes("/proc/self/cmdline", 1 << 20);
  std::vector<std::string> args;
  for (std::size_t i = 0; i < raw.size();) {
    const std::size_t end = raw.find('\0', i);
    args.push_back(raw.substr(i, end == std::string::npos ? std::string::npos : end - i));
    if (end == std::string::npos) break;
    i = end + 1;
  }
  std::vector<std::string> out;
  for (std::size_t i = 1; i < args.size(); ++i) {  // args[0]: the program
    if (args[i] == "--nproc") {
      ++i;
      continue;
    }
    if (args[i].rfind("--nproc=", 0) == 0) continue;
    out.push_back(args[i]);
  }
  return out;
}

std::string status_text(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return "was killed by signal " + std::to_string(sig) + " (" + std::string(::strsignal(sig)) + ")";
  }
  return "exited with status " + std::to_string(WEXITSTATUS(status));
}

}  // namespace

void run_local_ranks(int nproc, double grace_s) {
  if (nproc < 1 || nproc > kMaxRanks)
    throw Error("--nproc: must be in 1-" + std::to_string(kMaxRanks) + ", found " + std::to_string(nproc));
  const std::vector<std::string> base = own_arguments();
  const std::string rendezvous = "tcp://127.0.0.1:" + std::to_string(free_port());
  ::setenv(kDistTokenVariable, random_token().c_str(), 1);  // the ranks inherit it
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction sa {};
    sa.sa_handler = forward_signal;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
  std::vector<pid_t> pids;
  for (int r = 0; r < nproc; ++r) {
    std::vector<std::string> args{"ptnet"};
    args.insert(args.end(), base.begin(), base.end());
    for (const std::string& a : {std::string("--world-size"), std::to_string(nproc), std::string("--rank"),
                                 std::to_string(r), std::string("--rendezvous"), rendezvous})
      args.push_back(a);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) {
      signal_ranks(SIGTERM);
      throw Error("train --nproc: cannot start rank " + std::to_string(r) + " (fork failed)");
    }
    if (pid == 0) {
      for (int sig : {SIGINT, SIGTERM, SIGHUP}) ::signal(sig, SIG_DFL);
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // the launcher killed (even -9): the ranks stop too
      ::execv("/proc/self/exe", argv.data());
      ::_exit(127);
    }
    g_children[std::size_t(r)].store(pid);
    pids.push_back(pid);
  }
  // Wait for every rank; after the first failure the others get grace_s to
  // stop by themselves (they notice the lost rank), then SIGTERM, SIGKILL.
  using Clock = std::chrono::steady_clock;
  int running = nproc, failed_rank = -1, failed_status = 0;
  Clock::time_point failed_at;
  bool termed = false, killed = false;
  while (running > 0) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid > 0) {
      const int r = int(std::find(pids.begin(), pids.end(), pid) - pids.begin());
      if (r < nproc) {
        g_children[std::size_t(r)].store(0);
        --running;
        const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
        if (!ok && failed_rank < 0) failed_rank = r, failed_status = status, failed_at = Clock::now();
      }
      continue;
    }
    if (pid < 0 && errno != EINTR) break;
    const double since = failed_rank >= 0 ? std::chrono::duration<double>(Clock::now() - failed_at).count() : 0;
    if (failed_rank >= 0 && !termed && since > grace_s) signal_ranks(SIGTERM), termed = true;
    if (failed_rank >= 0 && !killed && since > grace_s + 5) signal_ranks(SIGKILL), killed = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (const int sig = g_signal.load(); sig != 0) {  // Ctrl-C: die of it, as a single process would
    ::signal(sig, SIG_DFL);
    ::raise(sig);
  }
  if (failed_rank >= 0)
    throw Error("train --nproc " + std::to_string(nproc) + ": rank " + std::to_string(failed_rank) + " " +
                status_text(failed_status) + "; every rank has stopped");
}

}  // namespace ptnet::cli
