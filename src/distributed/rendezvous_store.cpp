// The rendezvous stores of a distributed run (see rendezvous_store.hpp): the
// tcp store's client (the wire format: store_protocol.hpp; the server:
// store_server.cpp) and the file store's guarded creation.
#include "rendezvous_store.hpp"

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <torch/csrc/distributed/c10d/FileStore.hpp>

#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"
#include "store_protocol.hpp"

namespace ptnet {
using namespace store_protocol;
namespace {

constexpr auto kCheckInterval = std::chrono::milliseconds(10);   // wait(): between checks
constexpr auto kRetryInterval = std::chrono::milliseconds(100);  // connecting: between attempts
constexpr char kFileMarker[] = "ptnet/store";                     // the first key of a file store

class TcpStore final : public c10d::Store {
 public:
  TcpStore(std::unique_ptr<StoreServer> server, std::string host, int port, std::chrono::milliseconds timeout,
           std::string token)
      : c10d::Store(timeout), host_(std::move(host)), port_(port), token_(std::move(token)), server_(std::move(server)) {
    connect();
  }
  ~TcpStore() override {
    if (fd_ >= 0) ::close(fd_);
  }

  void set(const std::string& key, const std::vector<uint8_t>& value) override {
    call(kSet, {key, text(value)});
  }
  std::vector<uint8_t> compareSet(const std::string& key, const std::vector<uint8_t>& expected,
                                  const std::vector<uint8_t>& desired) override {
    const std::string reply = call(kCompareSet, {key, text(expected), text(desired)});
    Fields f{reply};
    return bytes(reply_field(f));
  }
  std::vector<uint8_t> get(const std::string& key) override {
    wait({key});
    const std::string reply = call(kGet, {key});
    Fields f{reply};
    if (f.rest.empty() || f.rest[0] != '\1') throw std::runtime_error("key " + escaped(key) + " was deleted");
    f.rest.remove_prefix(1);
    return bytes(reply_field(f));
  }
  int64_t add(const std::string& key, int64_t value) override {
    const std::string reply = call(kAdd, {key, int_field(value)});
    Fields f{reply};
    const std::int64_t v = f.next_int();
    if (!f.complete()) malformed();
    return v;
  }
  bool deleteKey(const std::string& key) override { return flag(call(kDelete, {key})); }
  bool check(const std::vector<std::string>& keys) override {
    std::vector<std::string_view> fields(keys.begin(), keys.end());
    return flag(call(kCheck, fields));
  }
  int64_t getNumKeys() override {
    const std::string reply = call(kNumKeys, {});
    Fields f{reply};
    const std::int64_t v = f.next_int();
    if (!f.complete()) malformed();
    return v;
  }
  void wait(const std::vector<std::string>& keys) override { wait(keys, timeout_); }
  // Bounded by the store's own timeout as well: Gloo asks for 300 s.
  void wait(const std::vector<std::string>& keys, const std::chrono::milliseconds& timeout) override {
    const auto bound = timeout > std::chrono::milliseconds::zero() ? std::min(timeout, timeout_) : timeout_;
    const auto deadline = Clock::now() + bound;
    while (!check(keys)) {
      if (Clock::now() > deadline)
        throw std::runtime_error("no key " + escaped(keys.empty() ? std::string() : keys[0]) + " within " +
                                 number_text(seconds_of(bound)) + " s");
      std::this_thread::sleep_for(kCheckInterval);
    }
  }

 private:
  static std::string text(const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); }
  static std::vector<uint8_t> bytes(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }
  [[noreturn]] void malformed() {
    broken_ = true;
    throw std::runtime_error("a malformed reply from the store at " + where());
  }
  std::string reply_field(Fields& f) {
    std::string s = f.next();
    if (!f.complete()) malformed();
    return s;
  }
  bool flag(const std::string& reply) {
    if (reply.size() != 1) malformed();
    return reply[0] == '\1';
  }
  std::string where() const { return host_ + ":" + std::to_string(port_); }

  // Connects and greets, retrying until the timeout (rank 0 may not be
  // listening yet). A greeting answered by a closed connection (another
  // token, or every slot taken) is the reason given when none succeeds.
  void connect() {
    const auto deadline = Clock::now() + timeout_;
    std::string why = "no address", refused;
    for (;;) {
      Addresses a(host_, port_, /*passive=*/false);
      for (const addrinfo* p = a.list; p && fd_ < 0; p = p->ai_next) {
        fd_ = ::socket(p->ai_family, p->ai_socktype | SOCK_CLOEXEC | SOCK_NONBLOCK, p->ai_protocol);
        if (fd_ < 0) {
          why = errno_text();
          continue;
        }
        try {
          if (::connect(fd_, p->ai_addr, p->ai_addrlen) != 0 && errno != EINPROGRESS)
            throw std::runtime_error(errno_text());
          await(POLLOUT, deadline);
          int err = 0;
          socklen_t len = sizeof err;
          ::getsockopt(fd_, SOL_SOCKET, SO_ERROR, &err, &len);
          if (err != 0) throw std::runtime_error(errno_text(err));
          const int one = 1;
          ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
          broken_ = closed_ = false;
          try {
            call(kHello, {kGreeting, token_});
          } catch (const std::exception&) {
            if (closed_)
              refused = "the store closed the connection at the greeting: another " + field_text("dist_token") +
                        " than rank 0's, or every slot taken";
            throw;
          }
        } catch (const std::exception& e) {
          why = e.what();
          ::close(fd_);
          fd_ = -1;
        }
      }
      if (fd_ >= 0) return;
      if (Clock::now() > deadline)
        throw Error("could not reach rank 0 at " + where() + " within " + number_text(seconds_of(timeout_)) +
                    " s (" + (refused.empty() ? why : refused) + ")");
      std::this_thread::sleep_for(kRetryInterval);
    }
  }

  // Waits until fd_ is ready for `events`, at most until `deadline`.
  void await(short events, Clock::time_point deadline) {
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) throw std::runtime_error("no answer from " + where() + " within " +
                                              number_text(seconds_of(timeout_)) + " s");
      pollfd p{fd_, events, 0};
      const int n = ::poll(&p, 1, int(std::min<long long>(left, 1000)));
      if (n > 0) return;
      if (n < 0 && errno != EINTR) throw std::runtime_error("poll: " + errno_text());
    }
  }

  // One request and its reply's fields (after the status byte); a refusal
  // is an Error with the server's reason; a lost or silent connection
  // breaks this client (later calls fail at once).
  std::string call(Op op, std::initializer_list<std::string_view> fields) {
    return call(op, std::vector<std::string_view>(fields));
  }
  std::string call(Op op, const std::vector<std::string_view>& fields) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (broken_ || fd_ < 0) throw std::runtime_error("the connection to the store at " + where() + " was lost");
    const std::string body = request(op, fields);
    if (body.size() > kMaxStoreMessage) throw Error("a store message of " + std::to_string(body.size()) + " bytes");
    const auto deadline = Clock::now() + timeout_;
    std::string reply;
    try {
      const std::string out = framed(body);
      for (std::size_t sent = 0; sent < out.size();) {
        await(POLLOUT, deadline);
        const ssize_t n = ::send(fd_, out.data() + sent, out.size() - sent, MSG_NOSIGNAL);
        if (n < 0 && errno != EAGAIN && errno != EINTR) throw std::runtime_error(errno_text());
        if (n > 0) sent += std::size_t(n);
      }
      std::string in;
      for (std::size_t want = 4; in.size() < want;) {
        await(POLLIN, deadline);
        char buf[65536];
        const ssize_t n = ::recv(fd_, buf, std::min(sizeof buf, want - in.size()), 0);
        if (n == 0) {
          closed_ = true;
          throw std::runtime_error("the store at " + where() + " closed the connection");
        }
        if (n < 0 && errno != EAGAIN && errno != EINTR) throw std::runtime_error(errno_text());
        if (n > 0) in.append(buf, std::size_t(n));
        if (want == 4 && in.size() == 4) {
          if (get_u32(in.data()) > kMaxStoreMessage || get_u32(in.data()) == 0)
            throw std::runtime_error("a malformed reply from the store at " + where());
          want = 4 + get_u32(in.data());
        }
      }
      reply = in.substr(4);
    } catch (const std::exception&) {
      broken_ = true;
      throw;
    }
    if (reply[0] == '\1') throw Error("the store at " + where() + " refused: " + one_line(reply.substr(1)));
    return reply.substr(1);
  }

  std::string host_;
  int port_ = 0;
  std::string token_;                    // the run's, sent with the greeting
  std::unique_ptr<StoreServer> server_;  // rank 0 only
  std::mutex mutex_;
  int fd_ = -1;
  bool broken_ = false;
  bool closed_ = false;  // the store closed the connection (the last call's answer)
};

// The bytes c10d::FileStore writes first for key `key` (its records: a
// native u32 length and the bytes of "/KEY", then the value the same way).
std::string file_store_record_start(const std::string& key) {
  const std::string k = "/" + key;
  const std::uint32_t n = std::uint32_t(k.size());
  return std::string(reinterpret_cast<const char*>(&n), sizeof n) + k;
}

std::string kind_of(const struct stat& st) {
  if (S_ISREG(st.st_mode)) return "a file of " + std::to_string(st.st_size) + " bytes";
  if (S_ISLNK(st.st_mode)) return "a symbolic link";
  return file_kind(st.st_mode);
}

// True when `path` (found as `st`) is a regular file beginning with
// `start`; `st` gets what was opened. Never blocks: a FIFO is not opened.
bool begins_with(const std::string& path, struct stat& st, const std::string& start) {
  if (!S_ISREG(st.st_mode)) return false;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  std::string found(start.size(), '\0');
  const bool ok = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) &&
                  ::read(fd, found.data(), found.size()) == ssize_t(found.size()) && found == start;
  ::close(fd);
  return ok;
}

}  // namespace

c10::intrusive_ptr<c10d::Store> tcp_store(const std::string& host, int port, bool serve, int world_size,
                                         std::chrono::milliseconds timeout, const std::string& token) {
  // Every rank holds one connection; a few more greeted ones (a rank
  // restarting its connection) are served, beyond that they are closed.
  std::unique_ptr<StoreServer> server;
  if (serve) server = std::make_unique<StoreServer>(host, port, world_size + 8, token);
  return c10::make_intrusive<TcpStore>(std::move(server), host, port, timeout, token);
}

c10::intrusive_ptr<c10d::Store> file_store(const std::string& path, int rank, int world_size,
                                          std::chrono::milliseconds timeout) {
  namespace fs = std::filesystem;
  struct stat st {};
  if (rank == 0) {
    if (::lstat(path.c_str(), &st) == 0)
      throw Error("found " + path + " already there (" + kind_of(st) +
                  "); rank 0 creates the rendezvous file: give a path that does not exist (remove one left "
                  "from an earlier run)");
    // The file appears complete with its first record, never empty: the
    // record is written to a temporary file linked into place (link fails
    // rather than replace a file that appeared meanwhile).
    const fs::path target(path);
    const std::string temp =
        (target.parent_path() / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()))).string();
    ::unlink(temp.c_str());
    int linked = -1, err = 0;
    try {
      auto first = c10::make_intrusive<c10d::FileStore>(temp, world_size);
      first->setTimeout(timeout);
      first->set(kFileMarker, std::vector<uint8_t>{'1'});
      linked = ::link(temp.c_str(), path.c_str());
      err = errno;
      ::unlink(temp.c_str());  // before `first` goes: FileStore leaves a missing file alone
    } catch (const std::exception& e) {
      ::unlink(temp.c_str());
      throw Error("could not create " + path + " (" + one_line(e.what()) + ")");
    }
    if (linked != 0) throw Error("could not create " + path + " (" + errno_text(err) + ")");
  } else {
    const auto deadline = Clock::now() + timeout;
    while (::stat(path.c_str(), &st) != 0) {
      if (errno != ENOENT) throw Error("could not reach rank 0 (" + path + ": " + errno_text() + ")");
      if (Clock::now() > deadline)
        throw Error("could not reach rank 0 within " + number_text(seconds_of(timeout)) + " s (" + path +
                    " was not created)");
      std::this_thread::sleep_for(kRetryInterval);
    }
    if (!begins_with(path, st, file_store_record_start(kFileMarker)))
      throw Error("found " + path + " (" + kind_of(st) +
                  "), which is not a rendezvous file made by rank 0: give a path that does not exist");
  }
  auto store = c10::make_intrusive<c10d::FileStore>(path, world_size);
  store->setTimeout(timeout);
  return store;
}

}  // namespace ptnet
