// Simulator throughput, 80 x 28 mat, default options (3 x 3 samples per cell,
// default sensor):
//   BM_SimulateWalk/real        frames/s on one core, a real walking clip of
//                               ../shared/mocap (005_01, 30 fps) on a 175 cm body
//   BM_SimulateWalk/procedural  the same on the procedural walk (always runs)
//   BM_SimulateAllClips         every clip of ../shared/mocap, one core (fixed
//                               placement: frames off the mat cost little)
//   BM_SimulateAllClips/follow  the same with the mat following the body (every
//                               frame on the mat, as the corpus benchmark)
//   BM_SimulateMany/threads:2   simulate_many on 2 threads (8 jobs)
//   BM_SimulateDataset          the whole simulate_dataset path (load, retarget,
//                               simulate, compress, write) on 2 threads
// Aim: >= 20,000 frames/s per core. Run with --benchmark_format=json.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace {

namespace fs = std::filesystem;
const std::string kMocap = PTNET_SHARED_MOCAP;

const ptnet::Body& body175() {
  static const ptnet::Body b(ptnet::BodySpec{"b", ptnet::Sex::male, 175, 72, "retargeted"});
  return b;
}

ptnet::Motion procedural_walk() {
  ptnet::GenerateOptions g;
  g.category = ptnet::Category::walking;
  g.seconds = 20;
  g.seed = 3;
  return ptnet::retarget(ptnet::generate_motion(g), 175);
}

// Every clip of ../shared/mocap retargeted to 175 cm (empty if absent).
const std::vector<ptnet::Motion>& mocap() {
  static const std::vector<ptnet::Motion> clips = [] {
    std::vector<ptnet::Motion> out;
    const std::string csv = kMocap + "/clips.csv";
    if (!fs::exists(csv)) return out;
    for (const auto& c : ptnet::clips_from_files({}, csv, {}))
      out.push_back(ptnet::retarget(ptnet::load_clip(c, 30), 175));
    return out;
  }();
  return clips;
}

void run_frames(benchmark::State& state, const ptnet::Motion& m) {
  ptnet::SimOptions o;
  long frames = 0;
  for (auto _ : state) {
    ptnet::PressureSequence s = ptnet::simulate(m, body175(), o);
    benchmark::DoNotOptimize(s.kpa.data());
    frames += m.size();
  }
  state.counters["frames_per_s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
}

void BM_SimulateWalk_real(benchmark::State& state) {
  for (const auto& m : mocap())
    if (m.name == "005_01") return run_frames(state, m);
  state.SkipWithError("../shared/mocap not found: no real walking clip");
}
BENCHMARK(BM_SimulateWalk_real)->Name("BM_SimulateWalk/real")->Unit(benchmark::kMillisecond);

void BM_SimulateWalk_procedural(benchmark::State& state) {
  static const ptnet::Motion m = procedural_walk();
  run_frames(state, m);
}
BENCHMARK(BM_SimulateWalk_procedural)->Name("BM_SimulateWalk/procedural")->Unit(benchmark::kMillisecond);

void BM_SimulateAllClips(benchmark::State& state, ptnet::Placement placement) {
  if (mocap().empty()) return state.SkipWithError("../shared/mocap not found");
  ptnet::SimOptions o;
  o.placement = placement;
  long frames = 0;
  for (auto _ : state)
    for (const auto& m : mocap()) {
      ptnet::PressureSequence s = ptnet::simulate(m, body175(), o);
      benchmark::DoNotOptimize(s.kpa.data());
      frames += m.size();
    }
  state.counters["frames_per_s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_SimulateAllClips, fixed, ptnet::Placement::fixed)->Name("BM_SimulateAllClips")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateAllClips, follow, ptnet::Placement::follow)->Unit(benchmark::kMillisecond);

void BM_SimulateMany(benchmark::State& state) {
  const int threads = int(state.range(0));
  static const ptnet::Motion walk = procedural_walk();
  const ptnet::Motion* m = &walk;
  for (const auto& c : mocap())
    if (c.name == "005_01") m = &c;
  std::vector<ptnet::SimJob> jobs;
  for (int i = 0; i < 8; ++i) jobs.push_back({m, &body175(), std::uint64_t(i), nullptr, {}});
  ptnet::SimOptions o;
  long frames = 0;
  for (auto _ : state) {
    auto out = ptnet::simulate_many(jobs, o, threads);
    benchmark::DoNotOptimize(out.data());
    frames += long(jobs.size()) * m->size();
  }
  state.counters["frames_per_s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateMany)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SimulateDataset(benchmark::State& state) {
  const std::vector<ptnet::ClipSource> clips = ptnet::embedded_clips(1, 1, 8, 1);
  std::vector<ptnet::BodySpec> bodies;
  for (int i = 0; i < 4; ++i)
    bodies.push_back({"b" + std::to_string(i), i % 2 ? ptnet::Sex::male : ptnet::Sex::female, 160.0 + 8 * i,
                      60.0 + 6 * i, "retargeted"});
  const std::string out = (fs::temp_directory_path() / "ptnet_bench_sim.h5").string();
  ptnet::SimulateDatasetOptions o;
  o.threads = 2;
  o.force = true;
  long frames = 0;
  for (auto _ : state) frames += ptnet::simulate_dataset(clips, bodies, out, o).frames;
  fs::remove(out);
  state.counters["frames_per_s"] = benchmark::Counter(double(frames), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateDataset)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
