// ptnet demo: the embedded default, no external data. Procedural motions
// (performers x 4 categories x 2 takes) retargeted onto 8 + 8 sampled bodies and
// 2 + 2 held-out original bodies, simulated on the 80 x 28 mat, written as a
// dataset with a figure of one motion on two bodies. Every output stays in the
// folder so each later step (train, evaluate, render) can be rerun on it.
#include <filesystem>
#include <iostream>

#include "command.hpp"
#include "ptnet/body.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "ptnet/viz.hpp"

namespace ptnet::cli {
namespace {

struct DemoCli {
  std::string out = "demo";
  int performers = 5, takes = 2, threads = 0;
  double seconds = 8;
  std::uint64_t seed = 1;
  bool force = false;
};

void run(const DemoCli& c) {
  namespace fs = std::filesystem;
  const bool quiet = globals().quiet;
  fs::create_directories(c.out);
  const std::string data_path = (fs::path(c.out) / "data.h5").string();
  const std::string bodies_path = (fs::path(c.out) / "bodies.csv").string();
  const std::string figure_path = (fs::path(c.out) / "walking_two_bodies.png").string();
  for (const auto& p : {data_path, bodies_path, figure_path}) check_output_path(p, c.force);

  const auto bodies = sample_bodies(8, 8, 2, 2, c.seed);
  write_text_file(bodies_path, format_bodies_csv(bodies), c.force);

  const std::vector<ClipSource> clips = embedded_clips(c.performers, c.takes, c.seconds, c.seed);
  if (!quiet) std::cerr << "demo: " << clips.size() << " procedural clips on " << bodies.size() << " bodies\n";
  SimulateDatasetOptions so;
  so.seed = c.seed;
  so.threads = c.threads;
  so.force = c.force;
  so.generator = std::string("ptnet ") + PTNET_VERSION + " demo";
  so.config_json = "{\"performers\": " + std::to_string(c.performers) + ", \"takes\": " +
                   std::to_string(c.takes) + ", \"seconds\": " + std::to_string(c.seconds) +
                   ", \"seed\": " + std::to_string(c.seed) + "}";
  so.progress = [quiet](const std::string& phase, int done, int total) {
    if (!quiet && phase == "simulate" && (done % 50 == 0 || done == total))
      std::cerr << "simulate: " << done << "/" << total << " sequences\r" << (done == total ? "\n" : "") << std::flush;
  };
  simulate_dataset(clips, bodies, data_path, so);
  const Dataset d = Dataset::open(data_path);
  const std::string motion = "p1_walking_t1";
  FigureOptions fo;
  fo.cop = true;
  render_figure(d, {motion + "__" + bodies.front().id, motion + "__" + bodies[8].id}, figure_path, fo, c.force);
  std::cout << describe_dataset(d, false) << "\n";
  std::cout << "wrote " << bodies_path << "\nwrote " << data_path << "\nwrote " << figure_path << "\n"
            << "next: ptnet train --data " << data_path << " --out " << c.out << "/model --preset fast\n"
            << "      ptnet evaluate --model " << c.out << "/model --data " << data_path << " --out " << c.out
            << "/report\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<DemoCli>();
  auto* cmd = app.add_subcommand("demo", "The embedded default: procedural motions, bodies, simulation, figure");
  cmd->add_option("--out", c->out, "Output folder")->capture_default_str();
  cmd->add_option("--performers", c->performers, "Procedural performers")->capture_default_str()->check(CLI::Range(1, 50));
  cmd->add_option("--takes", c->takes, "Takes per performer and category")->capture_default_str()->check(CLI::Range(1, 5));
  cmd->add_option("--seconds", c->seconds, "Seconds per clip")->capture_default_str()->check(CLI::Range(2.0, 120.0));
  cmd->add_option("--seed", c->seed, "Seed")->capture_default_str();
  cmd->add_option("--threads", c->threads, "Simulation threads (0: all cores)")->capture_default_str();
  cmd->add_flag("--force", c->force, "Overwrite existing outputs");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(90, setup);
}  // namespace ptnet::cli
