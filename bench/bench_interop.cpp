// The C++ side of python/bench_interop.py: the same calls the Python module
// makes, timed without Python (docs/results.md, "Python interop").
//   BM_InteropRmse       rmse of two 80 x 28 frames (a call's fixed cost)
//   BM_InteropSimulate   a 4 s procedural walk retargeted onto a 180 cm body and
//                        simulated (place_copy), as ptnet.simulate does
//   BM_InteropTransfer   Transfer::run of 120 frames with the model folder in
//                        $PTNET_BENCH_MODEL (skipped when unset)
// Run with --benchmark_format=json.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/transfer.hpp"

namespace {

ptnet::Motion walk() {
  ptnet::GenerateOptions g;
  g.seconds = 4;
  g.seed = 3;
  return ptnet::generate_motion(g);
}

void BM_InteropRmse(benchmark::State& state) {
  std::vector<float> a(80 * 28, 1.0f), b(80 * 28, 2.0f);
  for (auto _ : state) benchmark::DoNotOptimize(ptnet::rmse(a.data(), b.data(), a.size()));
}
BENCHMARK(BM_InteropRmse);

void BM_InteropSimulate(benchmark::State& state) {
  const ptnet::Motion m = walk();
  const ptnet::BodySpec spec{"b", ptnet::Sex::male, 180, 80, "retargeted"};
  ptnet::SimOptions o;
  o.seed = 1;
  for (auto _ : state) {
    const ptnet::Body body(spec);
    const ptnet::Motion copy = ptnet::retarget(m, spec.height_cm);
    auto seq = ptnet::simulate(copy, body, o, ptnet::place_copy(m, spec.height_cm, o));
    benchmark::DoNotOptimize(seq.kpa.data());
  }
  state.counters["frames"] = m.size();
}
BENCHMARK(BM_InteropSimulate)->Unit(benchmark::kMillisecond);

void BM_InteropTransfer(benchmark::State& state) {
  const char* dir = std::getenv("PTNET_BENCH_MODEL");
  if (!dir) {
    state.SkipWithError("PTNET_BENCH_MODEL unset (a model folder)");
    return;
  }
  const ptnet::Transfer net(dir);
  const ptnet::Motion m = walk();
  const ptnet::BodySpec src{"s", ptnet::Sex::female, 165, 60, "retargeted"}, dst{"t", ptnet::Sex::male, 185, 95, ""};
  ptnet::SimOptions o;
  ptnet::PressureSequence seq = ptnet::simulate(ptnet::retarget(m, 165), ptnet::Body(src), o);
  for (auto _ : state) benchmark::DoNotOptimize(net.run(seq, src, dst).kpa.data());
}
BENCHMARK(BM_InteropTransfer)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
