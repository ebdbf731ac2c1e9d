// distributed/store_protocol.hpp: the wire format of the tcp rendezvous store,
// shared by its server (store_server.cpp) and its client
// (rendezvous_store.cpp). Private to the distributed stage.
//
// A message is a u32 length N (little-endian, N <= kMaxStoreMessage) and N
// bytes: an op byte, then fields, each a u32 length and its bytes (an
// integer is a field of 8 bytes, little-endian). A reply is a message whose
// first byte is 0 (done, then its fields) or 1 (refused, then the reason).
// A connection's first message is kHello with the greeting and the run's
// token (DistOptions::token): a connection that sends anything else, or
// another token, is closed before it may do anything.
#pragma once

#include <netdb.h>
#include <sys/socket.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "ptnet/error.hpp"
#include "rendezvous_store.hpp"

namespace ptnet::store_protocol {

using Clock = std::chrono::steady_clock;
inline constexpr char kGreeting[] = "ptnet-store 2";
inline constexpr std::size_t kGreetingMessage = 512;  // largest message before the greeting (it holds the token)
// The greeting (an op byte, the greeting and the token, each after its 4-byte length) must fit.
static_assert(kGreetingMessage >= 1 + 4 + sizeof(kGreeting) + 4 + kMaxToken, "kGreetingMessage too small for kMaxToken");

// Equal secrets, compared in a time that does not depend on where they differ.
inline bool same_secret(std::string_view a, std::string_view b) {
  unsigned char differ = a.size() != b.size();
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) differ |= std::uint8_t(a[i] ^ b[i]);
  return differ == 0;
}

enum Op : std::uint8_t { kHello = 1, kSet, kGet, kAdd, kCheck, kDelete, kNumKeys, kCompareSet };

inline void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += char((v >> (8 * i)) & 0xffu);
}
inline std::uint32_t get_u32(const char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= std::uint32_t(std::uint8_t(p[i])) << (8 * i);
  return v;
}
inline void put_field(std::string& out, std::string_view s) {
  put_u32(out, std::uint32_t(s.size()));
  out += s;
}
inline std::string int_field(std::int64_t v) {
  std::string s(8, '\0');
  for (int i = 0; i < 8; ++i) s[std::size_t(i)] = char((std::uint64_t(v) >> (8 * i)) & 0xffu);
  return s;
}
// A whole message: its length, then `body`.
inline std::string framed(const std::string& body) {
  std::string out;
  put_u32(out, std::uint32_t(body.size()));
  return out + body;
}

// The body of a request: its op byte, then its fields.
template <class Field>
std::string request(Op op, const std::vector<Field>& fields) {
  std::string body(1, char(op));
  for (const auto& f : fields) put_field(body, f);
  return body;
}

// The fields of a message body, in order (a view: the body must outlive
// it); `bad` once one is malformed.
struct Fields {
  std::string_view rest;
  bool bad = false;
  std::string next() {
    if (rest.size() < 4 || rest.size() - 4 < get_u32(rest.data())) {
      bad = true;
      return {};
    }
    const std::uint32_t n = get_u32(rest.data());
    std::string s(rest.substr(4, n));
    rest.remove_prefix(4 + std::size_t(n));
    return s;
  }
  std::int64_t next_int() {
    const std::string s = next();
    if (s.size() != 8) bad = true;
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < s.size() && i < 8; ++i) v |= std::uint64_t(std::uint8_t(s[i])) << (8 * i);
    return std::int64_t(v);
  }
  bool complete() const { return !bad && rest.empty(); }
};

inline std::string errno_text(int e = errno) { return std::strerror(e); }

// "[::1]" as written in a URL -> "::1".
inline std::string bare_host(const std::string& host) {
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') return host.substr(1, host.size() - 2);
  return host;
}

struct Addresses {
  addrinfo* list = nullptr;
  Addresses(const std::string& host, int port, bool passive) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_NUMERICSERV | (passive ? AI_PASSIVE : 0);
    const int rc = ::getaddrinfo(bare_host(host).c_str(), std::to_string(port).c_str(), &hints, &list);
    if (rc != 0) throw Error("cannot resolve " + escaped(host) + " (" + ::gai_strerror(rc) + ")");
  }
  ~Addresses() {
    if (list) ::freeaddrinfo(list);
  }
  Addresses(const Addresses&) = delete;
  Addresses& operator=(const Addresses&) = delete;
};

inline double seconds_of(std::chrono::milliseconds t) { return double(t.count()) / 1000.0; }

}  // namespace ptnet::store_protocol
