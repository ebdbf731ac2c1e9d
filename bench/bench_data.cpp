// Dataset file speed: write throughput (MB/s of raw float32), compression
// ratio on realistic sparse pressure (synthetic_walk foot blobs), and read
// throughput of random 30-frame windows.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "ptnet/data.hpp"
#include "support/synthetic_walk.hpp"

namespace {
constexpr int kSequences = 8;      // 4 motions x 2 bodies
constexpr int kFrames = 600;       // 20 s at 30 fps each
constexpr int kWindow = 30;        // frames per model window

std::string temp_path(const char* tag) {
  return (std::filesystem::temp_directory_path() / (std::string("ptnet_bench_") + tag + std::to_string(::getpid()) + ".h5")).string();
}

std::vector<ptnet::PressureSequence> make_sequences() {
  std::vector<ptnet::PressureSequence> out;
  for (int i = 0; i < kSequences; ++i)
    out.push_back(ptnet::synthetic_walk(ptnet::MatSpec{}, kFrames, 30, i % 2 ? 185 : 160, i % 2 ? 90 : 55, i));
  return out;
}

void write_dataset(const std::string& path, const std::vector<ptnet::PressureSequence>& seqs) {
  ptnet::DatasetInfo info;
  std::vector<ptnet::BodySpec> bodies = {{"b0", ptnet::Sex::female, 160, 55}, {"b1", ptnet::Sex::male, 185, 90}};
  ptnet::DatasetWriter w(path, info, bodies, true);
  for (int i = 0; i < kSequences; ++i) {
    ptnet::SequenceMeta m;
    m.name = "m" + std::to_string(i / 2) + "__b" + std::to_string(i % 2);
    m.body_id = "b" + std::to_string(i % 2);
    m.motion_id = "m" + std::to_string(i / 2);
    m.category = "walking";
    w.add(m, seqs[i]);
  }
  w.commit();
}

void BM_DatasetWrite(benchmark::State& state) {
  const auto seqs = make_sequences();
  const std::string path = temp_path("w");
  const double raw = double(kSequences) * kFrames * 80 * 28 * 4;
  for (auto _ : state) write_dataset(path, seqs);
  state.SetBytesProcessed(int64_t(state.iterations() * raw));
  state.counters["compression_ratio"] = raw / double(std::filesystem::file_size(path));
  state.counters["file_MB"] = std::filesystem::file_size(path) / 1e6;
  std::filesystem::remove(path);
}
BENCHMARK(BM_DatasetWrite)->Unit(benchmark::kMillisecond);

void BM_DatasetRandomWindows(benchmark::State& state) {
  const std::string path = temp_path("r");
  write_dataset(path, make_sequences());
  ptnet::Dataset d = ptnet::Dataset::open(path);
  std::vector<std::string> names;
  for (const auto& s : d.sequences()) names.push_back(s.name);
  std::mt19937_64 rng(1);
  std::vector<float> window(kWindow * 80 * 28);
  for (auto _ : state) {
    const auto& name = names[rng() % names.size()];
    const int start = int(rng() % (kFrames - kWindow + 1));
    d.read(name, start, kWindow, window.data());
    benchmark::DoNotOptimize(window.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(int64_t(state.iterations()) * window.size() * 4);
  std::filesystem::remove(path);
}
BENCHMARK(BM_DatasetRandomWindows)->Unit(benchmark::kMicrosecond);

void BM_DatasetSequentialWindows(benchmark::State& state) {
  const std::string path = temp_path("s");
  write_dataset(path, make_sequences());
  ptnet::Dataset d = ptnet::Dataset::open(path);
  std::vector<float> window(kWindow * 80 * 28);
  int start = 0;
  for (auto _ : state) {  // stride-1 windows through one sequence (training order)
    d.read("m0__b0", start, kWindow, window.data());
    start = (start + 1) % (kFrames - kWindow + 1);
    benchmark::DoNotOptimize(window.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(int64_t(state.iterations()) * window.size() * 4);
  std::filesystem::remove(path);
}
BENCHMARK(BM_DatasetSequentialWindows)->Unit(benchmark::kMicrosecond);
}  // namespace

BENCHMARK_MAIN();
