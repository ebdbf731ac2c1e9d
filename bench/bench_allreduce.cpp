// The cost of distributed training's one collective: a Gloo all-reduce (sum)
// of a float32 buffer between two ranks on 127.0.0.1, through the same
// Communicator as `ptnet train --world-size 2` (src/distributed/communicator.hpp).
// Sizes: the gradients of the fast preset's frame network and of the
// paper's network (what a step all-reduces), and 1 / 16 MB.
//
//   build/bench/bench_allreduce --benchmark_format=json
//
// The program forks its rank 1, which runs the same fixed schedule (no
// --benchmark_filter: the ranks must call the same all-reduces).
#include <benchmark/benchmark.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <torch/torch.h>

#include "distributed/communicator.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model_config.hpp"
#include "ptnet/train.hpp"

namespace {

constexpr int kIterations = 20;  // all-reduces per size (fixed: rank 1 mirrors them)
constexpr int kWarmUp = 3;

std::vector<std::int64_t> sizes() {  // floats
  ptnet::TrainOptions fast = ptnet::TrainOptions::from_preset("fast");
  return {ptnet::parameter_count(fast.model), ptnet::parameter_count(ptnet::ModelConfig::paper()),
          std::int64_t(1) << 18, std::int64_t(1) << 22};
}

ptnet::Communicator* g_comm = nullptr;

void all_reduce_once(std::int64_t floats) {
  std::vector<at::Tensor> t{torch::ones({floats})};
  g_comm->allreduce(t, "the benchmark");
}

void BM_AllReduce(benchmark::State& state) {
  const std::int64_t floats = sizes()[std::size_t(state.range(0))];
  for (int i = 0; i < kWarmUp; ++i) all_reduce_once(floats);
  for (auto _ : state) all_reduce_once(floats);
  state.SetBytesProcessed(state.iterations() * floats * 4);
  state.counters["bytes"] = double(floats * 4);
}
BENCHMARK(BM_AllReduce)->DenseRange(0, 3)->Iterations(kIterations)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  const std::string rendezvous = "file:///tmp/ptnet_bench_allreduce_" + std::to_string(::getpid());
  const pid_t child = ::fork();
  const int rank = child == 0 ? 1 : 0;
  try {
    auto comm = ptnet::Communicator::join({2, rank, rendezvous, 30});
    g_comm = comm.get();
    if (rank == 1) {  // the mirror: the same all-reduces, in the same order
      for (std::size_t s = 0; s < sizes().size(); ++s)
        for (int i = 0; i < kWarmUp + kIterations; ++i) all_reduce_once(sizes()[s]);
      std::_Exit(0);
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
  } catch (const ptnet::Error& e) {
    std::cerr << "bench_allreduce: " << e.what() << "\n";
    if (rank == 1) std::_Exit(1);
    return 1;
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  std::remove(rendezvous.substr(7).c_str());
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : 1;
}
