// Live streaming (ptnet::Stream, the library behind `ptnet stream`): the
// per-frame latency of push() -- p50, p99 and max in ms -- and the frames/s
// one thread sustains, on 300 frames of a simulated walk (10 s at 30 fps).
//
//   build/bench/bench_stream --benchmark_format=json
//
// Arguments: {widths} 2 = the fast preset's frame network (one frame per
// forward pass), 1 = the faithful window network at 16/32/64 (a 30-frame
// window per frame), 0 = the paper's 64/128/256. The model folder is written
// with random weights (speed does not depend on their values), or taken from
// $PTNET_BENCH_MODEL for widths 2 when set.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>

#include "ptnet/body.hpp"
#include "ptnet/io.hpp"
#include "ptnet/model.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/stream.hpp"
#include "ptnet/train.hpp"

namespace {

namespace fs = std::filesystem;

ptnet::ModelConfig config_for(int widths) {
  if (widths == 2) return ptnet::TrainOptions::from_preset("fast").model;  // the fast preset's frame network
  return widths == 0 ? ptnet::ModelConfig::paper() : ptnet::ModelConfig::fast();
}

// A model folder with random weights (eval-mode BatchNorm statistics set by one batch).
std::string model_folder(int widths) {
  const char* given = std::getenv("PTNET_BENCH_MODEL");
  if (widths == 2 && given) return given;
  const fs::path dir = fs::temp_directory_path() / ("ptnet_bench_stream_" + std::to_string(::getpid()) + "_" +
                                                    std::to_string(widths));
  fs::create_directories(dir);
  ptnet::ModelDir d;
  d.path = dir.string();
  d.model = config_for(widths);
  d.mat = ptnet::MatSpec{80, 28, 0.02};
  d.norm.pressure_scale_kpa = 100;
  d.norm.contact_threshold_kpa = 1;
  torch::manual_seed(0);
  ptnet::PressureTransferNet net(d.model);
  {
    torch::NoGradGuard no_grad;
    net->forward(torch::rand({4, d.model.window, 80, 28}), torch::randn({4, 3}), torch::randn({4, 3}));
  }
  net->eval();
  ptnet::save_weights(net, (dir / "model.pt").string());
  ptnet::write_text_file((dir / "config.json").string(), ptnet::to_json(d).dump(1), true);
  return d.path;
}

ptnet::PressureSequence walk() {
  ptnet::GenerateOptions g;
  g.seconds = 10;
  g.seed = 3;
  const ptnet::BodySpec body{"s", ptnet::Sex::female, 165, 60, "retargeted"};
  ptnet::SimOptions o;
  return ptnet::simulate(ptnet::retarget(ptnet::generate_motion(g), body.height_cm), ptnet::Body(body), o);
}

void BM_StreamFrame(benchmark::State& state) {
  const int widths = int(state.range(0));
  const std::string dir = model_folder(widths);
  const ptnet::PressureSequence rec = walk();
  const ptnet::BodySpec src{"s", ptnet::Sex::female, 165, 60, ""}, dst{"t", ptnet::Sex::male, 185, 95, ""};
  std::vector<double> ms;
  for (auto _ : state) {
    ptnet::StreamOptions o;
    o.threads = 1;
    ptnet::Stream live(dir, src, dst, o);
    std::vector<float> out(std::size_t(live.max_output_frames() * live.frame_cells()));
    for (int t = 0; t < rec.frames(); ++t) {
      const auto t0 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(live.push(rec.frame(t), out.data()));
      if (t >= live.max_output_frames())  // steady state: one frame out per frame in
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
  }
  std::sort(ms.begin(), ms.end());
  auto at = [&](double q) { return ms[std::size_t(q * double(ms.size() - 1) + 0.5)]; };
  state.counters["p50_ms"] = at(0.5);
  state.counters["p99_ms"] = at(0.99);
  state.counters["max_ms"] = ms.back();
  double total = 0;
  for (double v : ms) total += v;
  state.counters["frames_per_s"] = double(ms.size()) / (total / 1e3);
  if (!std::getenv("PTNET_BENCH_MODEL") || widths != 2) fs::remove_all(dir);
}
BENCHMARK(BM_StreamFrame)->Arg(2)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
