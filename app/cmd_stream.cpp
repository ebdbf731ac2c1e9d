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
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <vector>

#include "command.hpp"
#include "ptnet/body_spec.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/stream.hpp"

namespace ptnet::cli {
namespace {

struct StreamCli {
  std::string model, source, target, in = "-", format = "auto";
  int threads = 1;
  bool raw = false, stats = false;
};

// Reads up to n bytes (fewer only at end of input); throws Error on a read error.
std::size_t read_fully(int fd, char* data, std::size_t n, const std::string& name) {
  std::size_t got = 0;
  while (got < n) {
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
    if (read_fully(fd, head.data() + had, size - had, name) != size - had)
      throw Error::in(name, "npy header truncated");
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
  std::vector<double> latency_ms;
  for (long long t = 0; promised < 0 || t < promised; ++t) {
    const std::size_t got =
        pending + read_fully(fd, reinterpret_cast<char*>(frame.data()) + pending, frame_bytes - pending, name);
    pending = 0;
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
    latency_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  if (c.stats && !latency_ms.empty()) {
    std::sort(latency_ms.begin(), latency_ms.end());
    auto at = [&](double q) { return latency_ms[std::size_t(q * double(latency_ms.size() - 1) + 0.5)]; };
    std::fprintf(stderr, "stream: %zu frames, per-frame latency p50 %.3f ms, p99 %.3f ms, max %.3f ms\n",
                 latency_ms.size(), at(0.5), at(0.99), latency_ms.back());
  }
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
  cmd->add_flag("--stats", c->stats, "At the end, print the per-frame latency (p50, p99) on stderr");
  cmd->callback([c] { run(*c); });
}

}  // namespace

PTNET_COMMAND(56, setup);

}  // namespace ptnet::cli
