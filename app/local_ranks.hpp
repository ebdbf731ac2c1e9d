// app/local_ranks.hpp: `ptnet train --nproc N`, the ranks of a distributed
// run started on this machine (docs/distributed.md).
#pragma once

#include <string>
#include <vector>

namespace ptnet::cli {

// The environment variable `ptnet train` reads its rendezvous token
// (TrainOptions::dist_token) from.
inline constexpr char kDistTokenVariable[] = "PTNET_DIST_TOKEN";

// Starts N copies of this ptnet (/proc/self/exe) with this command line minus
// `--nproc N`, plus `--world-size N --rank R --rendezvous tcp://127.0.0.1:PORT`
// on a free port and a fresh random token in kDistTokenVariable (their
// environment, which other users cannot read, unlike a command line), and
// waits for them. When a rank fails, the others are
// given `grace_s` to notice and stop by themselves, then SIGTERM, then
// SIGKILL; Ctrl-C (SIGINT, SIGTERM, SIGHUP) is passed on to them all.
// Throws Error naming the first rank that failed.
void run_local_ranks(int nproc, double grace_s);

}  // namespace ptnet::cli
