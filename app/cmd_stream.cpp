// ptnet stream: live transfer. Pressure frames (float32 rows x cols, kPa) in
// on stdin or a FIFO, each transferred frame out on stdout as soon as its
// causal window is complete (ptnet/stream.hpp, docs/model.md "Live streaming").
//
//   producer | ptnet stream --model model/ --source female,165,60 --target male,185,95 > out.f32
//   ptnet stream --model model/ --source ... --target ... --in rec.npy --stats > out.f32
//
// Input: raw float32 little-endian frames, or a .npy stream (the \x93NUMPY
// header, shape [T, rows, cols], '<f4', then the frames); --format auto tells
// them apart by the magic. Output: raw float32 frames, the same count as in.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <vector>

#include "command.hpp"
#include "ptnet/body_spec.hpp"
#include "ptnet/latency.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/stream.hpp"

namespace ptnet::cli::cmd_stream {
namespace {

struct StreamCli {
  std::string model, source, target, in = "-", format = "auto";
  int threads = 1;
  bool raw = false, stats = false;
};

// Ctrl-C (SIGINT), SIGTERM or SIGHUP: the stream stops reading, prints its
// --stats and dies of the signal; a second one ends it at once. The handler
// wakes the reading thread through a pipe (whichever thread it runs on).
std::atomic<int> g_stop{0};
int g_wake[2] = {-1, -1};

extern "C" void request_stop(int sig) {
  if (g_stop.exchange(sig) != 0) {
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    return;
  }
  const char c = 0;
  [[maybe_unused]] const ssize_t n = ::write(g_wake[1], &c, 1);
}

void catch_stop_signals() {
  if (::pipe2(g_wake, O_CLOEXEC | O_NONBLOCK) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // ignored (nohup): leave it
    struct sigaction sa {};
    sa.sa_handler = request_stop;
    sa.sa_flags = SA_RESTART;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

// After the stream stopped on a signal: die of it, as an uncaught one would.
void die_of_stop_signal() {
  if (const int sig = g_stop.load(); sig != 0) {
    ::signal(sig, SIG_DFL);
    ::raise(sig);
  }
}

// Reads up to n bytes: fewer only at end of input or once a stop signal
// came; throws Error on a read error.
std::size_t read_fully(int fd, char* data, std::size_t n, const std::string& name) {
  std::size_t got = 0;
  while (got < n) {
    pollfd ready[2] = {{fd, POLLIN, 0}, {g_wake[0], POLLIN, 0}};
    if (::poll(ready, 2, -1) < 0 && errno != EINTR)
      throw Error::in(name, std::string("cannot wait for input: ") + std::strerror(errno));
    if (g_stop.load() != 0) break;
    if (ready[0].revents == 0) continue;
    const ssize_t r = ::read(fd, data + got, n - got);
    if (r == 0) break;
    if (r < 0) {
      if (errno == EINTR) continue;
      throw Error::in(name, std::string("cannot read: ") + std::strerror(errno));
    }
    got += std::size_t(r);
  }
  return got;
}

void write_fully(const float* data, std::size_t floats) {
  const char* p = reinterpret_cast<const char*>(data);
  std::size_t left = floats * sizeof(float);
  while (left > 0) {
    const ssize_t w = ::write(STDOUT_FILENO, p, left);
    if (w < 0) {
      if (errno == EINTR) continue;
      throw Error(std::string("stdout: cannot write: ") + std::strerror(errno));
    }
    p += w;
    left -= std::size_t(w);
  }
}

// The npy header from the stream (its first bytes already in `head`): the
// frames it promises, after checking dtype and mat.
long long read_npy_header(int fd, std::string head, const std::string& name, const ModelDir& d) {
  if (head.size() < 12) throw Error::in(name, "npy header truncated");
  const std::size_t size = npy_header_size(head, name);
  if (size > kMaxNpyHeaderBytes) throw Error::in(name, "npy header larger than 1 MiB");
  if (size > head.size()) {
    const std::size_t had = head.size();
    head.resize(size);
    if (read_fully(fd, head.data() + had, size - had, name) != size - had) {
      die_of_stop_signal();
      throw Error::in(name, "npy header truncated");
    }
  }
  const NpyHeader h = parse_npy_header(head, name);
  if (h.shape.size() != 3 || h.shape[1] != d.mat.rows || h.shape[2] != d.mat.cols) {
    std::string found;
    for (auto v : h.shape) found += (found.empty() ? "" : ", ") + std::to_string(v);
    throw Error::in(name, "expected shape [T, " + std::to_string(d.mat.rows) + ", " + std::to_string(d.mat.cols) +
                              "], found [" + found + "]");
  }
  return h.shape[0];
}

// At the end of an input that was not stopped: no bytes after the frames an
// npy header promised, and at least a window of frames.
void check_clean_end(int fd, long long promised, const Stream& live, const std::string& name) {
  char extra = 0;
  if (promised >= 0 && read_fully(fd, &extra, 1, name) > 0 && g_stop.load() == 0)
    throw Error::in(name, "more data after the " + std::to_string(promised) + " frames the npy header promises");
  const long long in = live.frames_in(), window = live.max_output_frames();
  if (in > 0 && in < window)
    throw Error::in(name, std::to_string(in) + " frame" + (in == 1 ? "" : "s") + ", fewer than the model's window of " +
                              std::to_string(window) + ": no frame was transferred");
}

void run(const StreamCli& c) {
  StreamOptions o;
  o.threads = c.threads;
  o.raw = c.raw;
  o.input_name = c.in == "-" ? "stdin" : c.in;
  const std::string& name = o.input_name;
  const BodySpec source = parse_body_attributes(c.source, "--source");
  const BodySpec target = parse_body_attributes(c.target, "--target");
  int fd = STDIN_FILENO;
  if (c.in != "-") {
    note_input(c.in);
    fd = ::open(c.in.c_str(), O_RDONLY);
    if (fd < 0) throw Error::in(c.in, std::string("cannot open: ") + std::strerror(errno));
  }
  struct Closer {
    int fd;
    ~Closer() {
      if (fd != STDIN_FILENO) ::close(fd);
    }
  } closer{fd};
  Stream live(c.model, source, target, o);
  catch_stop_signals();
  const std::size_t cells = std::size_t(live.frame_cells()), frame_bytes = cells * sizeof(float);

  // The first bytes tell a .npy stream from raw frames.
  std::vector<float> frame(cells), out(cells * std::size_t(live.max_output_frames()));
  std::string head(12, '\0');
  std::size_t have = read_fully(fd, head.data(), head.size(), name);
  head.resize(have);
  const bool npy_magic = have >= 6 && std::memcmp(head.data(), "\x93NUMPY", 6) == 0;
  if (c.format == "npy" && !npy_magic) throw Error::in(name, "expected a .npy stream (the \\x93NUMPY magic)");
  long long promised = -1;  // frames the npy header announces
  std::size_t pending = have;  // bytes of the first raw frame already read
  if (npy_magic && c.format != "raw") {
    promised = read_npy_header(fd, head, name, live.model());
    pending = 0;
  } else {
    std::memcpy(frame.data(), head.data(), have);
  }
  if (!globals().quiet)
    std::cerr << "stream: " << (promised >= 0 ? "npy" : "raw float32") << " frames of "
              << live.model().mat.rows << " x " << live.model().mat.cols << ", window "
              << live.max_output_frames() << " (" << sex_name(source.sex) << " " << source.height_cm << " cm "
              << source.weight_kg << " kg -> " << sex_name(target.sex) << " " << target.height_cm << " cm "
              << target.weight_kg << " kg)\n";
  LatencySummary latency;  // with --stats: a fixed footprint however long the stream
  for (long long t = 0; promised < 0 || t < promised; ++t) {
    const std::size_t got =
        pending + read_fully(fd, reinterpret_cast<char*>(frame.data()) + pending, frame_bytes - pending, name);
    pending = 0;
    if (g_stop.load() != 0) break;  // a partly read frame is dropped
    if (got == 0) {
      if (promised >= 0)
        throw Error::in(name, "the npy header promises " + std::to_string(promised) + " frames, found " +
                                  std::to_string(t));
      break;  // end of input: a clean exit
    }
    if (got < frame_bytes)
      throw Error::in(name, "frame " + std::to_string(t) + " is short: expected " + std::to_string(frame_bytes) +
                                " bytes (" + std::to_string(live.model().mat.rows) + " x " +
                                std::to_string(live.model().mat.cols) + " float32), found " + std::to_string(got));
    const auto t0 = std::chrono::steady_clock::now();
    const int ready = live.push(frame.data(), out.data());
    write_fully(out.data(), std::size_t(ready) * cells);
    if (c.stats) latency.add(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  if (g_stop.load() == 0) check_clean_end(fd, promised, live, name);
  if (c.stats && latency.count() > 0)
    std::fprintf(stderr, "stream: %lld frames, per-frame latency p50 %.3f ms, p99 %.3f ms, max %.3f ms\n",
                 static_cast<long long>(latency.count()), latency.quantile(0.5), latency.quantile(0.99),
                 latency.max());
  die_of_stop_signal();
}

void setup(CLI::App& app) {
  auto c = std::make_shared<StreamCli>();
  auto* cmd = app.add_subcommand(
      "stream",
      "Live transfer: read pressure frames (float32 rows x cols kPa, raw or a .npy stream) from stdin\n"
      "or a FIFO and write each transferred frame (raw float32, same layout) to stdout as soon as its\n"
      "causal window of the model's frames is complete (docs/model.md, \"Live streaming\").");
  cmd->add_option("--model", c->model, "Model folder (ptnet train)")->required();
  cmd->add_option("--source", c->source, "Source body SEX,HEIGHT_CM,WEIGHT_KG, e.g. female,165,60")->required();
  cmd->add_option("--target", c->target, "Target body SEX,HEIGHT_CM,WEIGHT_KG, e.g. male,185,95")->required();
  cmd->add_option("--in", c->in, "Input file or FIFO ('-': stdin)")->capture_default_str();
  cmd->add_option("--format", c->format, "auto (by the .npy magic) | raw | npy")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "raw", "npy"}));
  cmd->add_option("--threads", c->threads, "CPU threads (0 = LibTorch default)")
      ->capture_default_str()
      ->check(thread_count(true));
  cmd->add_flag("--raw", c->raw, "Raw network output: skip the model's fitted contact threshold");
  cmd->add_flag("--stats", c->stats,
                "At the end (of the input, or on Ctrl-C / SIGTERM), print the per-frame latency (p50, p99, "
                "max) on stderr");
  cmd->callback([c] { run(*c); });
}

}  // namespace

PTNET_COMMAND(56, setup);

}  // namespace ptnet::cli::cmd_stream
