// The tcp rendezvous store's server, run by rank 0 (see rendezvous_store.hpp;
// the wire format: store_protocol.hpp): one thread, a poll loop over every
// connection, never blocking on one.
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <thread>
#include <vector>

#include "store_protocol.hpp"

namespace ptnet {
using namespace store_protocol;
namespace {
constexpr int kServerTick = 100;  // ms: the server notices stop() within it

// A refusal the client reports (status 1 and the reason).
std::string refused(const std::string& why) { return framed(std::string(1, '\1') + why); }
std::string store_full() {
  return refused("the store is full (" + std::to_string(kMaxStoreBytes >> 20) + " MB of keys and values)");
}
}  // namespace

struct StoreServer::Impl {
  struct Client {
    int fd = -1;
    Clock::time_point opened;
    std::uint64_t tick = 0;  // the server's tick when accepted
    bool greeted = false;
    std::string in;        // the message being read: its length, then its body
    std::string out;       // the reply being written
    std::size_t sent = 0;  // bytes of `out` written
  };
  int listen_fd = -1, port = 0, max_clients = 0;
  std::string token;      // the run's: a connection's greeting must hold it
  std::uint64_t tick = 0;  // serve_once calls
  int greeted = 0;         // clients greeted: the run's ranks
  std::atomic<bool> stop{false};
  std::thread thread;
  std::vector<Client> clients;
  std::map<std::string, std::string> data;
  std::size_t bytes = 0;  // keys and values in `data`

  void loop();
  void serve_once();
  void accept_new(Clock::time_point now);
  bool read_from(Client& c);  // false: drop the connection
  bool write_to(Client& c);
  // The reply to one message, or "" to drop the connection.
  std::string answer(Client& c, std::string_view message);
  std::string add(Fields& f);          // the replies to kAdd and kCompareSet, "" to drop
  std::string compare_set(Fields& f);
  bool store(const std::string& key, std::string value);  // false: over kMaxStoreBytes
};

StoreServer::StoreServer(const std::string& host, int port, int max_clients, const std::string& token)
    : impl_(std::make_unique<Impl>()) {
  impl_->max_clients = max_clients;
  impl_->token = token;
  Addresses a(host, port, /*passive=*/true);
  std::string why = "no address";
  for (const addrinfo* p = a.list; p && impl_->listen_fd < 0; p = p->ai_next) {
    const int fd = ::socket(p->ai_family, p->ai_socktype | SOCK_CLOEXEC | SOCK_NONBLOCK, p->ai_protocol);
    if (fd < 0) {
      why = errno_text();
      continue;
    }
    const int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);  // a restart soon after a run
    if (::bind(fd, p->ai_addr, p->ai_addrlen) == 0 && ::listen(fd, 64) == 0) {
      impl_->listen_fd = fd;
      break;
    }
    why = errno_text();
    ::close(fd);
  }
  if (impl_->listen_fd < 0) throw Error("could not listen on " + host + ":" + std::to_string(port) + " (" + why + ")");
  sockaddr_storage bound{};
  socklen_t len = sizeof bound;
  ::getsockname(impl_->listen_fd, reinterpret_cast<sockaddr*>(&bound), &len);
  impl_->port = bound.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&bound)->sin6_port)
                                            : ntohs(reinterpret_cast<sockaddr_in*>(&bound)->sin_port);
  impl_->thread = std::thread([impl = impl_.get()] { impl->loop(); });
}

StoreServer::~StoreServer() {
  impl_->stop = true;
  if (impl_->thread.joinable()) impl_->thread.join();
  for (auto& c : impl_->clients) ::close(c.fd);
  ::close(impl_->listen_fd);
}

int StoreServer::port() const { return impl_->port; }

void StoreServer::Impl::loop() {
  try {
    while (!stop) serve_once();
  } catch (const std::exception&) {
    // Out of memory or out of descriptors: stop serving; the ranks' next
    // calls fail with a lost connection, each within its timeout.
  }
  for (auto& c : clients) ::close(c.fd);
  clients.clear();
}

void StoreServer::Impl::serve_once() {
  std::vector<pollfd> fds{{listen_fd, POLLIN, 0}};
  for (const auto& c : clients) fds.push_back({c.fd, short(c.out.empty() ? POLLIN : POLLOUT), 0});
  if (::poll(fds.data(), fds.size(), kServerTick) < 0 && errno != EINTR)
    throw std::runtime_error("poll: " + errno_text());
  const auto now = Clock::now();
  std::vector<Client> kept;
  for (std::size_t i = 0; i < clients.size(); ++i) {
    Client& c = clients[i];
    const short ev = fds[i + 1].revents;
    bool keep = true;
    if (ev & POLLOUT) keep = write_to(c);
    else if (ev & (POLLIN | POLLHUP | POLLERR)) keep = read_from(c);
    if (keep && !c.greeted && now - c.opened > kGreetingTime) keep = false;  // silent for too long
    if (keep) {
      kept.push_back(std::move(c));
    } else {
      ::close(c.fd);
      greeted -= c.greeted;
    }
  }
  clients = std::move(kept);
  if (fds[0].revents & POLLIN) accept_new(now);
  ++tick;
}

// New connections wait, ungreeted, among at most kMaxPending: beyond them
// the oldest one accepted in an earlier tick (whose greeting, had it sent
// one, has been read) is closed for the new one; with none such the new one
// is closed. Strangers keeping connections open cannot keep a rank out:
// its greeting follows its connection at once.
void StoreServer::Impl::accept_new(Clock::time_point now) {
  for (int fd; (fd = ::accept4(listen_fd, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC)) >= 0;) {
    if (int(clients.size()) - greeted >= kMaxPending) {
      const auto oldest = std::find_if(clients.begin(), clients.end(),
                                       [&](const Client& c) { return !c.greeted && c.tick < tick; });
      if (oldest == clients.end()) {
        ::close(fd);
        continue;
      }
      ::close(oldest->fd);
      clients.erase(oldest);
    }
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    Client c;
    c.fd = fd;
    c.opened = now;
    c.tick = tick;
    clients.push_back(std::move(c));
  }
}

bool StoreServer::Impl::read_from(Client& c) {
  char buf[65536];
  for (;;) {
    // What is still missing of this message: its length, then its body.
    std::size_t want = 4;
    if (c.in.size() >= 4) {
      const std::uint32_t n = get_u32(c.in.data());
      if (n == 0 || n > (c.greeted ? kMaxStoreMessage : kGreetingMessage)) return false;  // never allocated
      want = 4 + std::size_t(n);
      if (c.in.size() == want) {
        c.out = answer(c, std::string_view(c.in).substr(4));
        c.in.clear();
        c.sent = 0;
        if (c.out.empty()) return false;
        return write_to(c);  // one message at a time: the next is read once this reply is out
      }
    }
    const ssize_t got = ::recv(c.fd, buf, std::min(sizeof buf, want - c.in.size()), 0);
    if (got == 0) return false;
    if (got < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    c.in.append(buf, std::size_t(got));
  }
}

bool StoreServer::Impl::write_to(Client& c) {
  while (c.sent < c.out.size()) {
    const ssize_t n = ::send(c.fd, c.out.data() + c.sent, c.out.size() - c.sent, MSG_NOSIGNAL);
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    c.sent += std::size_t(n);
  }
  c.out.clear();
  c.sent = 0;
  return true;
}

bool StoreServer::Impl::store(const std::string& key, std::string value) {
  const auto it = data.find(key);
  const std::size_t old = it == data.end() ? 0 : key.size() + it->second.size();
  if (bytes - old + key.size() + value.size() > kMaxStoreBytes) return false;
  bytes = bytes - old + key.size() + value.size();
  data[key] = std::move(value);
  return true;
}

std::string StoreServer::Impl::answer(Client& c, std::string_view message) {
  if (message.empty()) return {};
  const auto op = std::uint8_t(message[0]);
  Fields f{message.substr(1)};
  std::string done(1, '\0');
  if (!c.greeted) {
    const std::string greeting = op == kHello ? f.next() : std::string(), token = f.next();
    if (op != kHello || greeting != kGreeting || !f.complete() || !same_secret(token, this->token)) return {};
    if (greeted >= max_clients) return {};  // every slot taken by the run's own ranks
    c.greeted = true;
    ++greeted;
    return framed(done);
  }
  switch (op) {
    case kSet: {
      std::string key = f.next(), value = f.next();
      if (!f.complete()) return {};
      return store(key, std::move(value)) ? framed(done) : store_full();
    }
    case kGet: {
      const std::string key = f.next();
      if (!f.complete()) return {};
      const auto it = data.find(key);
      done += it == data.end() ? '\0' : '\1';
      put_field(done, it == data.end() ? std::string() : it->second);
      return framed(done);
    }
    case kAdd:
      return add(f);
    case kCheck: {
      bool all = true;
      while (!f.rest.empty() && !f.bad) all = data.count(f.next()) > 0 && all;
      if (f.bad) return {};
      done += all ? '\1' : '\0';
      return framed(done);
    }
    case kDelete: {
      const std::string key = f.next();
      if (!f.complete()) return {};
      const auto it = data.find(key);
      done += it == data.end() ? '\0' : '\1';
      if (it != data.end()) {
        bytes -= key.size() + it->second.size();
        data.erase(it);
      }
      return framed(done);
    }
    case kNumKeys:
      if (!f.complete()) return {};
      put_field(done, int_field(std::int64_t(data.size())));
      return framed(done);
    case kCompareSet:
      return compare_set(f);
    default:
      return {};
  }
}

std::string StoreServer::Impl::add(Fields& f) {
  const std::string key = f.next();
  const std::int64_t delta = f.next_int();
  if (!f.complete()) return {};
  long long now = 0;
  if (const auto it = data.find(key); it != data.end()) {
    char* end = nullptr;
    errno = 0;
    now = std::strtoll(it->second.c_str(), &end, 10);
    if (it->second.empty() || *end != '\0' || errno != 0)
      return refused("the value of " + escaped(key) + " is not a number");
  }
  const long long sum = (long long)(std::uint64_t(now) + std::uint64_t(delta));  // wraps, never traps
  if (!store(key, std::to_string(sum))) return store_full();
  std::string done(1, '\0');
  put_field(done, int_field(sum));
  return framed(done);
}

std::string StoreServer::Impl::compare_set(Fields& f) {
  std::string key = f.next(), expected = f.next(), desired = f.next();
  if (!f.complete()) return {};
  const auto it = data.find(key);
  std::string result;
  if ((it == data.end() && expected.empty()) || (it != data.end() && it->second == expected)) {
    if (!store(key, desired)) return store_full();
    result = desired;
  } else {
    result = it == data.end() ? expected : it->second;
  }
  std::string done(1, '\0');
  put_field(done, result);
  return framed(done);
}

}  // namespace ptnet
