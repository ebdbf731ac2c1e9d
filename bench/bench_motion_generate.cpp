// Procedural motions, retargeting and canonical BVH export: frames per second.
//
//   build/bench/bench_motion_generate --benchmark_format=json
#include <benchmark/benchmark.h>

#include "ptnet/motion.hpp"

namespace {

ptnet::Motion clip(ptnet::Category c, double seconds) {
  ptnet::GenerateOptions o;
  o.category = c;
  o.seconds = seconds;
  return ptnet::generate_motion(o);
}

void BM_Generate(benchmark::State& state) {
  const auto c = ptnet::kCategories[std::size_t(state.range(0))];
  int frames = 0;
  for (auto _ : state) {
    const ptnet::Motion m = clip(c, 30);
    frames += m.size();
    benchmark::DoNotOptimize(m.frames.data());
  }
  state.counters["frames_per_s"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
  state.SetLabel(ptnet::category_name(c));
}
BENCHMARK(BM_Generate)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_Retarget(benchmark::State& state) {
  const ptnet::Motion m = clip(ptnet::Category::walking, 30);
  int frames = 0;
  for (auto _ : state) {
    const ptnet::Motion r = ptnet::retarget(m, 160);
    frames += r.size();
    benchmark::DoNotOptimize(r.frames.data());
  }
  state.counters["frames_per_s"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Retarget)->Unit(benchmark::kMillisecond);

void BM_MotionToBvh(benchmark::State& state) {
  const ptnet::Motion m = clip(ptnet::Category::walking, 30);
  int frames = 0;
  for (auto _ : state) {
    const ptnet::Bvh b = ptnet::motion_to_bvh(m);
    frames += b.frames();
    benchmark::DoNotOptimize(b.values.data());
  }
  state.counters["frames_per_s"] = benchmark::Counter(frames, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MotionToBvh)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
