// PressureTransferNet speed on this CPU: training windows/s, inference
// windows/s, single-window latency, achieved GFLOP/s and its ratio to the
// measured peak of a large float32 torch::mm, for 1 and 2 threads.
//
//   build/bench/bench_model --benchmark_format=json
//
// Arguments: {threads, widths[, batch]} with widths 0 = the paper's
// 64/128/256 (the default architecture), 1 = the same network at 16/32/64,
// 2 = the fast preset's frame network (16/32/48, FiLM MLP 64, contact head,
// window 1: a "window" is one frame). BM_Inference/BM_Latency run the module
// (the reference); BM_InferenceFolded/BM_LatencyFolded the InferenceNet that
// Transfer and Stream use (BatchNorm and FiLM folded, InferenceMode).
// bench/compare_python.py runs the same networks in PyTorch beside these.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <map>

#include "model/model_config_internal.hpp"
#include "ptnet/model.hpp"
#include "ptnet/train.hpp"

namespace {

using ptnet::ModelConfig;

ModelConfig config_for(int widths) {
  if (widths == 0) return ModelConfig::paper();
  if (widths == 1) return ModelConfig::fast();
  return ptnet::TrainOptions::from_preset("fast").model;  // the fast preset's frame network
}

// An eval-mode network whose BatchNorm statistics are not the identity.
ptnet::PressureTransferNet eval_net(const ModelConfig& c) {
  torch::manual_seed(0);
  ptnet::PressureTransferNet net(c);
  net->train();
  {
    torch::NoGradGuard no_grad;
    net->forward(torch::rand({4, c.window, c.rows, c.cols}), torch::randn({4, 3}), torch::randn({4, 3}));
  }
  net->eval();
  return net;
}

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
  const int n = state.range(2) > 0 ? int(state.range(2)) : 32;
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
BENCHMARK(BM_TrainStep)->ArgsProduct({{1, 2}, {0, 1}, {32}})->Unit(benchmark::kMillisecond)->UseRealTime();
// The micro-batch (TrainOptions::micro_batch) by measurement: one thread, batches 8-64.
BENCHMARK(BM_TrainStep)->ArgsProduct({{1}, {0, 1, 2}, {8, 16, 64}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TrainStep)->Args({1, 2, 32})->Unit(benchmark::kMillisecond)->UseRealTime();

// Inference on batches of 64 windows (eval mode, no grad).
void BM_Inference(benchmark::State& state) {
  const int threads = int(state.range(0));
  const ModelConfig c = config_for(int(state.range(1)));
  const double peak = peak_gflops(threads);
  torch::set_num_threads(threads);
  ptnet::PressureTransferNet net = eval_net(c);
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
BENCHMARK(BM_Inference)->ArgsProduct({{1, 2}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// One window at a time (interactive use).
void BM_Latency(benchmark::State& state) {
  const int threads = int(state.range(0));
  const ModelConfig c = config_for(int(state.range(1)));
  torch::set_num_threads(threads);
  ptnet::PressureTransferNet net = eval_net(c);
  torch::NoGradGuard no_grad;
  auto x = torch::rand({1, c.window, c.rows, c.cols});
  auto a = torch::randn({1, 3});
  for (auto _ : state) benchmark::DoNotOptimize(net->forward(x, a, a));
}
BENCHMARK(BM_Latency)->ArgsProduct({{1, 2}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// The InferenceNet on batches of `batch` windows, all of one body pair (as
// Transfer::run): {threads, widths, batch}.
void BM_InferenceFolded(benchmark::State& state) {
  const int threads = int(state.range(0));
  const ModelConfig c = config_for(int(state.range(1)));
  const int n = int(state.range(2));
  torch::set_num_threads(threads);
  ptnet::InferenceNet net(eval_net(c));
  auto x = torch::rand({n, c.window, c.rows, c.cols});
  auto a = torch::randn({1, 3}).expand({n, 3});
  for (auto _ : state) benchmark::DoNotOptimize(net.forward(x, a, a));
  state.counters["windows_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["GFLOPs"] =
      benchmark::Counter(ptnet::forward_flops(c) * n / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_InferenceFolded)->ArgsProduct({{1, 2}, {0, 1, 2}, {64}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_InferenceFolded)->ArgsProduct({{1}, {0, 1, 2}, {8, 16, 32, 128}})->Unit(benchmark::kMillisecond)->UseRealTime();

// One window (one frame for widths 2) at a time through the InferenceNet: the live case.
void BM_LatencyFolded(benchmark::State& state) {
  const int threads = int(state.range(0));
  const ModelConfig c = config_for(int(state.range(1)));
  torch::set_num_threads(threads);
  ptnet::InferenceNet net(eval_net(c));
  auto x = torch::rand({1, c.window, c.rows, c.cols});
  auto a = torch::randn({1, 3});
  std::vector<double> ms;  // per call: the median is robust to preemption on a busy machine
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(net.forward(x, a, a));
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  state.counters["p50_ms"] = ms[ms.size() / 2];
  state.counters["p99_ms"] = ms[std::size_t(0.99 * double(ms.size() - 1) + 0.5)];
}
BENCHMARK(BM_LatencyFolded)->ArgsProduct({{1, 2}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// The layout choice of InferenceNet (MemoryLayout): {widths, batch, layout}
// with layout 1 = contiguous (NCHW), 2 = channels-last (NHWC); one thread.
void BM_InferenceLayout(benchmark::State& state) {
  const ModelConfig c = config_for(int(state.range(0)));
  const int n = int(state.range(1));
  torch::set_num_threads(1);
  ptnet::InferenceNet net(eval_net(c), state.range(2) == 2 ? ptnet::MemoryLayout::channels_last
                                                            : ptnet::MemoryLayout::contiguous);
  auto x = torch::rand({n, c.window, c.rows, c.cols});
  auto a = torch::randn({1, 3}).expand({n, 3});
  for (auto _ : state) benchmark::DoNotOptimize(net.forward(x, a, a));
  state.counters["windows_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_InferenceLayout)->ArgsProduct({{0, 1, 2}, {1, 64}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
