// Reading inputs and guarding outputs (ptnet/io.hpp): the one place where a
// run decides what it may read into memory and what it may replace.
#include "ptnet/io.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "core/io_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace fs = std::filesystem;

const char* file_kind(unsigned mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISREG(mode)) return "a regular file";
  return "not a regular file";
}

namespace {

// ------------------------------------------------------------ inputs

struct FileId {
  dev_t dev;
  ino_t ino;
  std::string path;
};
std::mutex g_inputs_mutex;
std::vector<FileId> g_inputs;


// Throws if `path` exists as something an output may not replace: not a
// regular file, or (after the `exists` check of check_output_path) an input.
void check_regular(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return;  // absent (or a dangling link): a new file
  if (!S_ISREG(st.st_mode))
    throw Error::in(path, std::string("is ") + file_kind(st.st_mode) +
                              ", not a regular file; refusing to replace it (even with " +
                              field_text("force") + ")");
}

void check_not_input(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return;
  std::lock_guard<std::mutex> lock(g_inputs_mutex);
  for (const FileId& in : g_inputs) {
    if (in.dev != st.st_dev || in.ino != st.st_ino) continue;
    struct stat now;  // the input still there (not deleted and its inode reused)
    if (::stat(in.path.c_str(), &now) != 0 || now.st_dev != in.dev || now.st_ino != in.ino) continue;
    throw Error::in(path, "is the same file as the input " + in.path +
                              "; refusing to replace it (even with " + field_text("force") +
                              "): write the output elsewhere");
  }
}

// ------------------------------------------------------------ signal cleanup
//
// Live temporary files sit in fixed slots that the signal handler can walk
// without allocating: state 0 free, 1 being written, 2 holds a path.

constexpr int kSlots = 64;
constexpr std::size_t kSlotPath = 4096;
struct Slot {
  std::atomic<int> state{0};
  char path[kSlotPath];
};
Slot g_slots[kSlots];

extern "C" void remove_temps_and_die(int sig) {
  for (Slot& s : g_slots)
    if (s.state.load() == 2) ::unlink(s.path);
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered when the handler returns: the usual death by signal
}

void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0) continue;
      if (old.sa_handler != SIG_DFL) continue;  // ignored, or somebody else's handler: leave it
      struct sigaction sa {};
      sa.sa_handler = remove_temps_and_die;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

int claim_slot(const std::string& path) {
  install_handlers();
  if (path.size() >= kSlotPath) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int free = 0;
    if (g_slots[i].state.compare_exchange_strong(free, 1)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(2);
      return i;
    }
  }
  return -1;  // more than kSlots live temporaries: left to the stale-file sweep
}

void release_slot(int slot) {
  if (slot >= 0) g_slots[slot].state.store(0);
}

// Removes `.NAME.tmpPID` files beside `target` whose process is gone.
void remove_stale_temps(const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + ".tmp";
  fs::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::stol(digits);
    if (pid <= 0 || pid == long(::getpid())) continue;
    if (::kill(pid_t(pid), 0) == -1 && errno == ESRCH) {
      std::error_code rm;
      fs::remove(it->path(), rm);
    }
  }
}

thread_local CommitGroup* t_group = nullptr;

void check_replaceable(const std::string& path) {
  check_regular(path);
  check_not_input(path);
}

void rename_into_place(const std::string& temp, const std::string& path) {
  check_replaceable(path);
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec)
    throw Error::in(path, "cannot rename temporary file into place: " + ec.message(),
                    ErrorKind::io);
}

}  // namespace

// ------------------------------------------------------------ reading

namespace {

// Opens `path` for InputFile: its descriptor, or -1 with what keeps it from
// being read in `problem` (and its kind).
int open_regular(const std::string& path, std::uint64_t& size, std::string& problem, ErrorKind& kind) {
  const auto not_regular = [&](mode_t mode) {
    kind = ErrorKind::format;  // as Error::in has it
    problem = S_ISDIR(mode) ? "is a folder, expected a file"
                            : std::string("is ") + file_kind(mode) + ", expected a regular file";
    return -1;
  };
  struct stat st {};
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);  // a FIFO opens at once; a socket does not
  if (fd < 0) {
    const int err = errno;
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return not_regular(st.st_mode);
    kind = err == ENOENT ? ErrorKind::not_found : ErrorKind::io;
    problem = err == ENOENT ? "no such file" : std::string("cannot open: ") + std::strerror(err);
    return -1;
  }
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return not_regular(st.st_mode);
  }
  size = std::uint64_t(st.st_size);
  return fd;
}

}  // namespace

InputFile::InputFile(const std::string& path) : path_(path) {
  std::string problem;
  ErrorKind kind = ErrorKind::format;
  fd_ = open_regular(path, size_, problem, kind);
  if (fd_ < 0) throw Error::in(path, problem, kind);
}

InputFile::~InputFile() { ::close(fd_); }

std::size_t InputFile::read(char* out, std::size_t n) {
  std::size_t got = 0;
  while (got < n) {
    const ssize_t r = ::read(fd_, out + got, n - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) throw Error::in(path_, "read error (" + std::string(std::strerror(errno)) + ")", ErrorKind::io);
    if (r == 0) break;
    got += std::size_t(r);
  }
  return got;
}

std::string read_file_bytes(const std::string& path, std::uint64_t max_bytes) {
  InputFile in(path);
  if (in.size() > max_bytes)
    throw Error::in(path, bytes_text(in.size()) + ", more than the " + bytes_text(max_bytes) +
                              " this kind of file may have");
  check_memory(in.size(), path, "reading the file");
  std::string text;
  text.reserve(std::size_t(in.size()));
  char buf[1 << 16];
  for (std::size_t n; (n = in.read(buf, sizeof buf)) > 0;) {
    text.append(buf, n);
    if (text.size() > max_bytes)
      throw Error::in(path, "more than the " + bytes_text(max_bytes) + " this kind of file may have (it grew while read)");
  }
  return text;
}

std::string read_text_file(const std::string& path, std::uint64_t max_bytes) {
  std::string text = read_file_bytes(path, max_bytes);
  check_utf8(text, path);
  return text;
}

std::string input_file_problem(const std::string& path, ErrorKind* kind) {
  std::uint64_t size = 0;
  std::string problem;
  ErrorKind k = ErrorKind::format;
  const int fd = open_regular(path, size, problem, k);
  if (fd >= 0) ::close(fd);
  if (kind) *kind = k;
  return problem;
}

std::string resolved_path(const std::string& folder, const std::string& file) {
  return file.empty() || fs::path(file).is_absolute() ? file : (fs::path(folder) / file).string();
}

void note_input(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return;
  std::lock_guard<std::mutex> lock(g_inputs_mutex);
  for (FileId& in : g_inputs)
    if (in.dev == st.st_dev && in.ino == st.st_ino) {
      in.path = path;  // the latest name (an older one may be gone, its inode reused)
      return;
    }
  g_inputs.push_back({st.st_dev, st.st_ino, path});
}

// ------------------------------------------------------------ outputs

Error exists_error(const std::string& path, const std::string& alternative) {
  return Error::in(path, "exists; pass " + field_text("force") + " to overwrite" +
                             (alternative.empty() ? "" : " or " + alternative),
                   ErrorKind::exists);
}

bool existing_folder(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return false;
  if (!fs::is_directory(path, ec)) throw Error::in(path, "exists and is not a folder");
  return true;
}

// The one overwrite rule of every output: throws exists_error(path) if
// `path` exists and `force` is false.
static void check_overwrite(const std::string& path, bool force) {
  std::error_code ec;
  if (!force && fs::exists(path, ec)) throw exists_error(path);
}

void check_output_path(const std::string& path, bool force) {
  check_regular(path);
  check_overwrite(path, force);
  std::error_code ec;
  check_not_input(path);
  fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) parent = ".";
  if (!fs::is_directory(parent, ec))
    throw Error::in(path, "folder " + parent.string() + " does not exist", ErrorKind::not_found);
  if (::access(parent.c_str(), W_OK) != 0)
    throw Error::in(path, "folder " + parent.string() + " is not writable", ErrorKind::io);
}

void check_output_folder(const std::string& path, bool force) {
  std::error_code ec;
  if (existing_folder(path) && !force && !fs::is_empty(path, ec)) throw exists_error(path);
}

void make_folder(const std::string& path) {
  std::error_code ec;
  fs::create_directories(path, ec);
  if (!fs::is_directory(path))
    throw Error::in(path, "cannot create folder: " + (ec ? ec.message() : std::string("not a folder")), ErrorKind::io);
}

void check_outputs_in_folder(const std::string& dir, const std::vector<std::string>& files, bool force) {
  existing_folder(dir);
  for (const std::string& f : files) {
    const std::string path = (fs::path(dir) / f).string();
    check_regular(path);
    check_overwrite(path, force);
    check_not_input(path);
  }
}

AtomicFile::AtomicFile(std::string path, bool force) : path_(std::move(path)) {
  check_output_path(path_, force);
  fs::path p(path_);
  remove_stale_temps(p);
  temp_ = (p.parent_path() / ("." + p.filename().string() + ".tmp" + std::to_string(::getpid()))).string();
  slot_ = claim_slot(temp_);
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
    release_slot(slot_);
  }
}

void AtomicFile::commit() {
  if (t_group) {
    t_group->pending_.push_back({temp_, path_, slot_});
    committed_ = true;  // the group owns the temporary file now
    return;
  }
  rename_into_place(temp_, path_);
  committed_ = true;
  release_slot(slot_);
}

CommitGroup::CommitGroup() : outer_(t_group) { t_group = this; }

CommitGroup::~CommitGroup() {
  t_group = outer_;
  for (const Pending& p : pending_) {
    std::error_code ec;
    fs::remove(p.temp, ec);
    release_slot(p.slot);
  }
}

void CommitGroup::commit() {
  t_group = outer_;  // no more adoptions
  for (const Pending& p : pending_) check_replaceable(p.path);  // all or (nearly) nothing
  while (!pending_.empty()) {
    const Pending p = pending_.front();
    rename_into_place(p.temp, p.path);
    release_slot(p.slot);
    pending_.erase(pending_.begin());
  }
}

void write_text_file(const std::string& path, const std::string& text, bool force) {
  AtomicFile out(path, force);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    if (!f)
      throw Error::in(path, std::string("cannot write: ") + std::strerror(errno), ErrorKind::io);
    f << text;
    f.flush();
    if (!f) throw Error::in(path, "write failed (disk full?)", ErrorKind::io);
  }
  out.commit();
}

// ------------------------------------------------------------ sizes

namespace {

// MemAvailable of /proc/meminfo (else the free pages), 0 if unknown.
std::uint64_t system_available_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  const long pages = ::sysconf(_SC_AVPHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? std::uint64_t(pages) * std::uint64_t(size) : 0;
}

// This process's address space, bytes (/proc/self/statm), 0 if unknown.
std::uint64_t address_space_bytes() {
  std::ifstream in("/proc/self/statm");
  std::uint64_t pages = 0;
  const long size = ::sysconf(_SC_PAGE_SIZE);
  return in >> pages && size > 0 ? pages * std::uint64_t(size) : 0;
}

}  // namespace

std::uint64_t available_memory_bytes() {
  std::uint64_t available = system_available_bytes();
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {  // ulimit -v
    const std::uint64_t used = address_space_bytes(), cap = std::uint64_t(limit.rlim_cur);
    const std::uint64_t room = cap > used ? cap - used : 1;  // 1, not 0: 0 is "unknown"
    available = available > 0 ? std::min(available, room) : room;
  }
  return available;
}

void check_memory(std::uint64_t bytes, const std::string& file, const std::string& what) {
  const std::uint64_t available = available_memory_bytes();
  if (available > 0 && bytes > available)
    throw Error::in(file, what + " needs " + bytes_text(bytes) + ", more than the " + bytes_text(available) +
                              " of available memory");
}

std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b, const std::string& file, const std::string& what) {
  std::uint64_t r = 0;
  if (__builtin_mul_overflow(a, b, &r)) throw Error::in(file, what + " overflows 64 bits");
  return r;
}

std::string bytes_text(std::uint64_t bytes) {
  char buf[32];
  if (bytes < 1000) std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  else if (bytes < 1000000) std::snprintf(buf, sizeof buf, "%.3g kB", double(bytes) / 1e3);
  else if (bytes < 1000000000) std::snprintf(buf, sizeof buf, "%.3g MB", double(bytes) / 1e6);
  else std::snprintf(buf, sizeof buf, "%.3g GB", double(bytes) / 1e9);
  return buf;
}

int max_threads() { return 4 * int(std::max(1u, std::thread::hardware_concurrency())); }

}  // namespace ptnet
