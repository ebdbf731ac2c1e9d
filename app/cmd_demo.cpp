// ptnet demo: the embedded default, no external data. Procedural motions
// (performers x 4 categories x 2 takes) retargeted onto 8 + 8 sampled bodies and
// 2 + 2 held-out original bodies, simulated on the 80 x 28 mat, written as a
// dataset with a figure of one motion on two bodies; then the fast preset is
// trained on it and evaluated (Table 2, report figures). Every output stays in
// the folder so each later step (train, evaluate, render) can be rerun on it.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <thread>

#include "command.hpp"
#include "ptnet/body.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "ptnet/train.hpp"
#include "ptnet/viz.hpp"

namespace ptnet::cli::cmd_demo {
namespace {

// Training threads (fewer on a one-core machine): on an idle 2-core machine
// 2 threads train the demo 1.5x faster than 1 (docs/model.md, "Threads").
constexpr int kDemoTrainThreads = 2;
// The fast preset in two thirds of its steps: 8 epochs, the learning rate
// halved every 3 (the preset: 12 and 4). On the demo's data (2-vCPU AMD
// EPYC, 2026-12-07) binary R^2 0.903 / 0.903 -> 0.901 / 0.901 seen /
// unseen, RMSE 1.10 / 1.07 -> 1.11 / 1.07 kPa (0.63 x / 0.62 x body
// scale), best validation loss 6.30e-5 -> 6.51e-5.
constexpr int kDemoEpochs = 8;
constexpr int kDemoLrHalveEvery = 3;

struct DemoCli {
  std::string out = "demo";
  EmbeddedCorpus corpus;
  int threads = 0;
  int train_threads = int(std::min(unsigned(kDemoTrainThreads), std::max(1u, std::thread::hardware_concurrency())));
  std::uint64_t seed = 1;
  int epochs = kDemoEpochs;
  bool force = false, no_train = false;
};

// Steps 2 and 3: the fast preset (mirrored) on the dataset, then the paper's Table 2.
void train_and_evaluate(const DemoCli& c, const std::string& data_path, const std::string& model_dir,
                        const std::string& report_dir) {
  const bool quiet = globals().quiet;
  if (!quiet)
    std::cerr << "demo: training (fast preset, --mirror on, --epochs " << c.epochs << " --lr-halve-every "
              << kDemoLrHalveEvery << ")\n";
  TrainOptions o = TrainOptions::from_preset("fast");
  o.epochs = c.epochs;
  o.lr_halve_every = kDemoLrHalveEvery;
  // Mirrored windows and mirror averaging (docs/model.md): on the demo's
  // data binary R^2 0.900 / 0.897 -> 0.903 / 0.903 seen / unseen, RMSE
  // 1.13 / 1.10 -> 1.10 / 1.07 kPa, at the same training cost.
  o.mirror = true;
  o.seed = c.seed;
  o.threads = c.train_threads;
  o.force = c.force;
  o.progress = train_progress();
  const auto source = open_dataset_source(data_path);
  const TrainResult t = train(*source, model_dir, o);
  print_warning("train", model_dir, t.warning);

  EvaluationRun r;
  r.model_dir = model_dir;
  r.data_path = data_path;
  r.out_dir = report_dir;
  r.force = c.force;
  r.progress = print;
  const EvaluationResult e = run_evaluation(r);
  print_warning("evaluate", ModelFiles(model_dir).config(), e.warning);
  char line[160];
  std::snprintf(line, sizeof line, "model: %s (%d epochs, best %d, %.0f s)", model_dir.c_str(), t.epochs_run,
                t.best_epoch, t.seconds);
  std::cout << "\n" << line << "\n\n" << e.table << "\n" << paper_table2_line() << "\n";
  for (const auto& p : e.written) std::cout << "wrote " << p << "\n";
  std::cout << "open " << e.page << " in a browser: the report on one page\n";
}

void run(const DemoCli& c) {
  namespace fs = std::filesystem;
  const bool quiet = globals().quiet;
  const std::string data_path = (fs::path(c.out) / "data.h5").string();
  const std::string bodies_path = (fs::path(c.out) / "bodies.csv").string();
  const std::string figure_path = (fs::path(c.out) / "walking_two_bodies.png").string();
  const std::string model_dir = (fs::path(c.out) / "model").string();
  const std::string report_dir = (fs::path(c.out) / "report").string();
  check_outputs_in_folder(c.out, {"data.h5", "bodies.csv", "walking_two_bodies.png"}, c.force);  // before creating it
  make_folder(c.out);
  if (!c.no_train)
    for (const auto& p : {model_dir, report_dir}) check_output_folder(p, c.force);

  const auto bodies = sample_bodies(8, 8, 2, 2, c.seed);
  write_text_file(bodies_path, format_bodies_csv(bodies), c.force);

  const std::vector<ClipSource> clips = embedded_clips(c.corpus.performers, c.corpus.takes, c.corpus.seconds, c.seed);
  if (!quiet) std::cerr << "demo: " << clips.size() << " procedural clips on " << bodies.size() << " bodies\n";
  SimulateDatasetOptions so;
  so.seed = c.seed;
  so.threads = c.threads;
  so.force = c.force;
  so.generator = std::string("ptnet ") + PTNET_VERSION + " demo";
  so.config_json = "{\"performers\": " + std::to_string(c.corpus.performers) + ", \"takes\": " +
                   std::to_string(c.corpus.takes) + ", \"seconds\": " + std::to_string(c.corpus.seconds) +
                   ", \"seed\": " + std::to_string(c.seed) + "}";
  so.progress = [](const Progress& p) {
    if (p.what == "simulate") print(p);
  };
  simulate_dataset(clips, bodies, data_path, so);
  const Dataset d = Dataset::open(data_path);
  const std::string motion = "p1_walking_t1";
  FigureOptions fo;
  fo.cop = true;
  render_figure(d, {motion + "__" + bodies.front().id, motion + "__" + bodies[8].id}, figure_path, fo, c.force);
  std::cout << describe_dataset(d, false) << "\n";
  std::cout << "wrote " << bodies_path << "\nwrote " << data_path << "\nwrote " << figure_path << "\n";
  if (c.no_train) {
    std::cout << "next: ptnet train --data " << data_path << " --out " << model_dir << " --preset fast --mirror on --epochs "
              << c.epochs << " --lr-halve-every " << kDemoLrHalveEvery << " --threads " << c.train_threads << "\n"
              << "      ptnet evaluate --model " << model_dir << " --data " << data_path << " --out "
              << report_dir << "\n";
    return;
  }
  train_and_evaluate(c, data_path, model_dir, report_dir);
}

void setup(CLI::App& app) {
  auto c = std::make_shared<DemoCli>();
  auto* cmd = app.add_subcommand(
      "demo", "The embedded default, no external data: procedural motions on sampled bodies, simulation,\n"
              "training (fast preset), evaluation (the paper's Table 2) and figures, all kept in --out");
  cmd->add_option("--out", c->out, "Output folder")->capture_default_str();
  const EmbeddedCorpusRanges& r = kEmbeddedCorpusRanges;
  cmd->add_option("--performers", c->corpus.performers, "Procedural performers")->capture_default_str()->check(int_range(r.performers));
  cmd->add_option("--takes", c->corpus.takes, "Takes per performer and category")->capture_default_str()->check(int_range(r.takes));
  cmd->add_option("--seconds", c->corpus.seconds, "Seconds per clip")->capture_default_str()->check(in_range(r.seconds));
  cmd->add_option("--seed", c->seed, "Seed")->capture_default_str();
  cmd->add_option("--threads", c->threads, "Simulation threads (0: all cores)")->capture_default_str()->check(thread_count(true));
  cmd->add_option("--train-threads", c->train_threads, "Training threads (the results depend on it)")
      ->capture_default_str()->check(thread_count(false));
  cmd->add_option("--epochs", c->epochs, "Training epochs (fast preset, the learning rate halved every 3)")->capture_default_str()->check(CLI::Range(1, 500));
  cmd->add_flag("--no-train", c->no_train, "Stop after the dataset and its figure");
  cmd->add_flag("--force", c->force, "Overwrite existing outputs");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(90, setup);
}  // namespace ptnet::cli::cmd_demo
