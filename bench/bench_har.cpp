// HAR stage benchmarks: window features, mean shift on ~20k PCA points,
// classifier training throughput (windows per second).
#include <benchmark/benchmark.h>

#include <random>

#include "har/har_internal.hpp"
#include "ptnet/har.hpp"

using namespace ptnet::har;

namespace {

// n windows [n, 30, 80, 28]: a few feet-sized blobs with noise.
WindowBatch random_windows(int n, std::uint64_t seed) {
  WindowBatch b;
  b.kpa.assign(std::size_t(n) * 30 * b.mat.cells(), 0.0f);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> row(0, 68), col(0, 22);
  for (int i = 0; i < n; ++i) {
    const int r0 = row(rng), c0 = col(rng);
    float* w = b.kpa.data() + std::size_t(i) * 30 * b.mat.cells();
    for (int t = 0; t < 30; ++t)
      for (int r = r0; r < r0 + 12; ++r)
        for (int c = c0; c < c0 + 5; ++c) w[t * b.mat.cells() + r * 28 + c] = 30.0f + t;
  }
  return b;
}

void BM_WindowFeatures(benchmark::State& state) {
  const WindowBatch b = random_windows(64, 1);
  for (auto _ : state) benchmark::DoNotOptimize(window_features(b));
  state.SetItemsProcessed(state.iterations() * 64);
}
BENCHMARK(BM_WindowFeatures)->Unit(benchmark::kMillisecond);

void BM_MeanShift20k(benchmark::State& state) {
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g(0, 1);
  const int n = 20000;
  Eigen::MatrixXd x(n, 4);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 4; ++j) x(i, j) = g(rng) + 6.0 * (i % 5) * (j == i % 4);
  int clusters = 0;
  for (auto _ : state) clusters = mean_shift(x, {}).clusters();
  state.counters["clusters"] = clusters;
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_MeanShift20k)->Unit(benchmark::kMillisecond);

void BM_ClassifierTrainEpoch(benchmark::State& state) {
  const int n = 1024;
  InputOptions io;
  io.pool = int(state.range(0));
  const PreparedWindows in = prepare_windows(random_windows(n, 3), io);
  std::vector<int> labels(n);
  for (int i = 0; i < n; ++i) labels[i] = i % 4;
  ClassifierOptions o;
  o.epochs = 1;
  o.batch_size = int(state.range(1));
  for (auto _ : state) {
    WindowClassifier net(in.channels, in.rows, in.cols, 4, o);
    net.train(in, labels);
  }
  state.SetItemsProcessed(state.iterations() * n);  // windows trained per second
}
BENCHMARK(BM_ClassifierTrainEpoch)
    ->Args({2, 64})
    ->Args({4, 64})
    ->Args({4, 128})
    ->Args({4, 256})
    ->Unit(benchmark::kMillisecond);  // pool, batch

}  // namespace

BENCHMARK_MAIN();
