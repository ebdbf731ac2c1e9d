// distributed/rendezvous_store.hpp: the key-value store through which the ranks of
// a distributed run meet (c10d::Store, used by Communicator::join and by
// Gloo's rendezvous). Private to the distributed stage.
//
//   auto store = tcp_store("127.0.0.1", 29500, /*serve=*/rank == 0, 2, 60s, token);
//   auto store = file_store("/shared/run.rdv", rank, 2, 60s);
//
// tcp: rank 0 serves the store on HOST:PORT, listening on the address HOST
// names only (127.0.0.1: this machine's loopback; 0.0.0.0: every
// interface); every rank, rank 0 too, is a client of it. Whoever else can
// reach the port can neither use, hold nor bloat the store: a connection
// must open with the store's greeting and the run's token (a secret every
// rank is given, kMinToken to kMaxToken bytes) or it is closed; until then
// it counts among at most kMaxPending waiting connections (a new one beyond
// them displaces the oldest that has had a chance to greet), and one that
// stays silent for kGreetingTime is closed. Only greeted connections take
// one of the `max_clients` slots. The server never blocks on one
// connection, refuses a message over kMaxStoreMessage and a store over
// kMaxStoreBytes, and stops at once when the run ends; every client call is
// bounded by the store's timeout.
//
// file: a c10d::FileStore on a shared filesystem. Rank 0 creates the file
// (it must not exist; it appears with its first record, never empty); the
// other ranks wait for it (up to the timeout) and join only a file that
// begins with that record. Any other existing path (a user's file, a
// folder) is refused and left untouched.
#pragma once

#include <torch/csrc/distributed/c10d/Store.hpp>

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>

namespace ptnet {

inline constexpr std::size_t kMaxStoreMessage = std::size_t(1) << 20;  // bytes of one request or reply
inline constexpr std::size_t kMaxStoreBytes = std::size_t(64) << 20;   // keys and values the server holds
inline constexpr auto kGreetingTime = std::chrono::seconds(10);        // a new connection's first message
inline constexpr int kMaxPending = 32;                                 // connections not yet greeted
inline constexpr std::size_t kMinToken = 16, kMaxToken = 256;          // bytes of a run's token

class StoreServer;

// The store of a tcp:// rendezvous; with `serve` (rank 0) this process
// also hosts the server. Every client greets with `token`. Throws Error
// when the server cannot listen or the client cannot reach it (or is
// refused: another token) within `timeout`.
c10::intrusive_ptr<c10d::Store> tcp_store(const std::string& host, int port, bool serve, int world_size,
                                         std::chrono::milliseconds timeout, const std::string& token);

// The store of a file:// rendezvous (see above). Throws Error naming
// `path` when it may not be used.
c10::intrusive_ptr<c10d::Store> file_store(const std::string& path, int rank, int world_size,
                                          std::chrono::milliseconds timeout);

// The server alone (tests): listens on host:port (port 0: the kernel's
// choice, see port()) until destroyed, for at most `max_clients` greeted
// connections (with `token`) at a time.
class StoreServer {
 public:
  StoreServer(const std::string& host, int port, int max_clients, const std::string& token);
  ~StoreServer();  // stops the server thread and closes every connection
  StoreServer(const StoreServer&) = delete;
  StoreServer& operator=(const StoreServer&) = delete;
  int port() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ptnet
