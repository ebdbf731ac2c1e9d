// distributed/communicator.hpp: the ranks of a data-parallel run, on PyTorch's
// c10d with the Gloo backend. Private to the distributed stage, which the train
// stage uses (its users see TrainOptions' world_size, rank, rendezvous,
// dist_timeout_s and dist_token, the fields the messages here name): c10d
// and Gloo are included by communicator.cpp (and the stores by
// rendezvous_store.cpp) only.
//
//   Communicator comm = Communicator::join({2, rank, "tcp://10.0.0.1:29500", 60, token});
//   comm.allreduce(tensors);      // sums in place over the ranks
//   comm.allreduce(values);       // doubles, the same
//
// Rendezvous (rendezvous_store.hpp): tcp://HOST:PORT (rank 0 serves the
// store on PORT, listening on the address HOST names only; every rank
// reaches it at HOST) or file://PATH (a c10d::FileStore on a shared
// filesystem; rank 0 creates the file, which must not exist). Every wait
// (joining, each collective) is bounded by `timeout_s`; a peer that dies
// closes its connections, so the survivors fail at their next collective.
// Every failure is a ptnet::Error of one line; a lost peer is named
// ("rank 1 was lost during the gradient all-reduce ...").
#pragma once

#include <ATen/core/Tensor.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ptnet {

struct DistOptions {
  int world_size = 1;      // ranks in the run
  int rank = 0;            // this process, 0 .. world_size - 1
  std::string rendezvous;  // tcp://HOST:PORT or file://PATH (world_size > 1)
  double timeout_s = 60;   // bound on joining and on every collective
  // tcp://: the run's secret, the same on every rank (kMinToken to kMaxToken
  // printable bytes, rendezvous_store.hpp): the store serves no connection
  // without it, so no one else can use, fill or end the run through it.
  std::string token;
};

// What the collectives cost (for the log and docs/distributed.md).
struct CommStats {
  std::int64_t calls = 0;  // all-reduces
  std::int64_t bytes = 0;  // payload bytes, summed over calls (this rank's buffers)
  double seconds = 0;      // wall time inside all-reduces
};

class Communicator {
 public:
  // Joins the run: checks that every rank was started with the same world
  // size and that no rank is taken twice. A world of one needs no rendezvous
  // and makes every call a no-op. Throws Error (bad address, timeout,
  // mismatch) of one line.
  static std::unique_ptr<Communicator> join(const DistOptions& options);
  ~Communicator();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool distributed() const { return size_ > 1; }

  // Sums float tensors (CPU, contiguous) in place over the ranks, as one
  // flat buffer. `what` names the collective in a failure message.
  void allreduce(std::vector<at::Tensor>& tensors, const std::string& what);
  // Sums doubles in place over the ranks.
  void allreduce(std::vector<double>& values, const std::string& what);
  // Throws Error naming `what` when the ranks hold different `values` (a
  // check that all were started on the same data, options and weights).
  void check_same(const std::vector<double>& values, const std::string& what);
  void barrier(const std::string& what);
  const CommStats& stats() const { return stats_; }

 private:
  struct Impl;
  Communicator(int rank, int size, std::unique_ptr<Impl> impl);
  [[noreturn]] void lost(const std::string& what, const std::string& detail);
  // The sum over ranks of buffer[0] in place, timed and counted in stats_.
  void sum(std::vector<at::Tensor>& buffer, const std::string& what);

  int rank_ = 0, size_ = 1;
  std::unique_ptr<Impl> impl_;
  CommStats stats_;
};

}  // namespace ptnet
