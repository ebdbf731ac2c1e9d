// Motion stage throughput on the real clips in ../shared/mocap, one core:
//   BM_ParseBvh   bytes_per_second  (aim >= 100 MB/s)
//   BM_Fk         joint_frames/s    (aim >= 1e6)
//   BM_LoadMotion clips/s for the whole read-map-resample-FK path
// Skips with a message when ../shared/mocap is absent.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "motion/motion_internal.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"

namespace {

const std::string kMocap = PTNET_SHARED_MOCAP;

struct Corpus {
  std::vector<std::string> names, texts;
  std::vector<ptnet::Bvh> clips;
};

const Corpus& corpus() {
  static const Corpus c = [] {
    Corpus c;
    if (!std::filesystem::exists(kMocap)) return c;
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(kMocap))
      if (e.path().extension() == ".bvh") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      c.names.push_back(f.string());
      c.texts.push_back(ptnet::read_text_file(f.string()));
      c.clips.push_back(ptnet::parse_bvh(c.texts.back(), f.string()));
    }
    return c;
  }();
  return c;
}

bool skip_if_absent(benchmark::State& state) {
  if (!corpus().texts.empty()) return false;
  state.SkipWithError("../shared/mocap not found: no real clips to benchmark");
  return true;
}

void BM_ParseBvh(benchmark::State& state) {
  if (skip_if_absent(state)) return;
  const Corpus& c = corpus();
  std::size_t bytes = 0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < c.texts.size(); ++i) {
      ptnet::Bvh b = ptnet::parse_bvh(c.texts[i], c.names[i]);
      benchmark::DoNotOptimize(b.values.data());
      bytes += c.texts[i].size();
    }
  }
  state.SetBytesProcessed(int64_t(bytes));
  state.counters["bytes_per_second"] =
      benchmark::Counter(double(bytes), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParseBvh)->Unit(benchmark::kMillisecond);

void BM_Fk(benchmark::State& state) {
  if (skip_if_absent(state)) return;
  const Corpus& c = corpus();
  double joint_frames = 0;
  for (auto _ : state) {
    for (const ptnet::Bvh& b : c.clips) {
      auto p = ptnet::forward_kinematics(b, 0.01, ptnet::UpAxis::y);
      benchmark::DoNotOptimize(p.data());
      joint_frames += double(b.frames()) * double(b.joints.size());
    }
  }
  state.counters["joint_frames_per_second"] =
      benchmark::Counter(joint_frames, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Fk)->Unit(benchmark::kMillisecond);

void BM_LoadMotion(benchmark::State& state) {
  if (skip_if_absent(state)) return;
  const Corpus& c = corpus();
  double clips = 0;
  for (auto _ : state) {
    for (const ptnet::Bvh& b : c.clips) {
      ptnet::Motion m = ptnet::motion_from_bvh(b, ptnet::MotionOptions{});
      benchmark::DoNotOptimize(m.frames.data());
      ++clips;
    }
  }
  state.counters["clips_per_second"] = benchmark::Counter(clips, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LoadMotion)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
