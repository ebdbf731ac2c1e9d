// PressureTransferNet speed on this CPU: training windows/s, inference
// windows/s, single-window latency, achieved GFLOP/s and its ratio to the
// measured peak of a large float32 torch::mm, for 1 and 2 threads.
//
//   build/bench/bench_model --benchmark_format=json
//
// Arguments: {threads, widths} with widths 0 = the paper's 64/128/256 (the
// default architecture), 1 = the fast preset's 16/32/64.
#include <benchmark/benchmark.h>

#include <chrono>
#include <map>

#include "ptnet/model.hpp"

namespace {

using ptnet::ModelConfig;

ModelConfig config_for(int widths) { return widths == 0 ? ModelConfig::paper() : ModelConfig::fast(); }

// GFLOP/s of a 2048 x 2048 float32 matrix product (cached per thread count).
double peak_gflops(int threads) {
  static std::map<int, double> cache;
  if (cache.count(threads)) return cache[threads];
  torch::set_num_threads(threads);
  const int n = 2048;
  auto a = torch::randn({n, n}), b = torch::randn({n, n});
  torch::mm(a, b);  // warm-up
  const int reps = 5;
  auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < reps; ++i) benchmark::DoNotOptimize(torch::mm(a, b));
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return cache[threads] = 2.0 * n * n * n * reps / s / 1e9;
}

void BM_PeakMatmul(benchmark::State& state) {
  const int threads = int(state.range(0));
  torch::set_num_threads(threads);
  const int n = 2048;
  auto a = torch::randn({n, n}), b = torch::randn({n, n});
  for (auto _ : state) benchmark::DoNotOptimize(torch::mm(a, b));
  state.counters["GFLOPs"] = benchmark::Counter(2.0 * n * n * n / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_PeakMatmul)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// One Adam step on a batch of 32 windows (forward + backward ~ 3x forward FLOPs).
void BM_TrainStep(benchmark::State& state) {
  const int threads = int(state.range(0));
  const ModelConfig c = config_for(int(state.range(1)));
  const double peak = peak_gflops(threads);
  torch::set_num_threads(threads);
  torch::manual_seed(0);
  ptnet::PressureTransferNet net(c);
  net->train();
  torch::optim::Adam opt(net->parameters(), torch::optim::AdamOptions(1e-3));
  const int n = 32;
  auto x = torch::rand({n, c.window, c.rows, c.cols}), y = torch::rand({n, c.window, c.rows, c.cols});
  auto a = torch::randn({n, 3});
  for (auto _ : state) {
    opt.zero_grad();
    auto loss = torch::mse_loss(net->forward(x, a, a), y);
    loss.backward();
    opt.step();
  }
  const double flops = 3.0 * ptnet::forward_flops(c) * n;
  state.counters["windows_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["GFLOPs"] = benchmark::Counter(flops / 1e9, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["peak_GFLOPs"] = peak;
}
BENCHMARK(BM_TrainStep)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

// Inference on batches of 64 windows (eval mode, no grad).
void BM_Inference(benchmark::State& state) {
  const int threads = int(state.range(0));
  const ModelConfig c = config_for(int(state.range(1)));
  const double peak = peak_gflops(threads);
  torch::set_num_threads(threads);
  ptnet::PressureTransferNet net(c);
  net->eval();
  torch::NoGradGuard no_grad;
  const int n = 64;
  auto x = torch::rand({n, c.window, c.rows, c.cols});
  auto a = torch::randn({n, 3});
  for (auto _ : state) benchmark::DoNotOptimize(net->forward(x, a, a));
  state.counters["windows_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["GFLOPs"] =
      benchmark::Counter(ptnet::forward_flops(c) * n / 1e9, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["peak_GFLOPs"] = peak;
}
BENCHMARK(BM_Inference)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

// One window at a time (interactive use).
void BM_Latency(benchmark::State& state) {
  const int threads = int(state.range(0));
  const ModelConfig c = config_for(int(state.range(1)));
  torch::set_num_threads(threads);
  ptnet::PressureTransferNet net(c);
  net->eval();
  torch::NoGradGuard no_grad;
  auto x = torch::rand({1, c.window, c.rows, c.cols});
  auto a = torch::randn({1, 3});
  for (auto _ : state) benchmark::DoNotOptimize(net->forward(x, a, a));
}
BENCHMARK(BM_Latency)->ArgsProduct({{1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
