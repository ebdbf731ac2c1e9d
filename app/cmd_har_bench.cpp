// ptnet har-bench: the body-shift HAR benchmark (docs/har_bench.md). Does
// transferred pressure help a classifier recognise people of bodies it
// never saw? Thin glue over ptnet/har_bench.hpp and ptnet/transfer.hpp.
//
//   ptnet har-bench --mocap corpus --write-training-set hb_train.h5
//   ptnet train --data hb_train.h5 --out hb_model --preset fast
//   ptnet har-bench --mocap corpus --model hb_model --model-data hb_train.h5 --out hb
#include <filesystem>
#include <iostream>
#include <optional>

#include "command.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har_bench.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/transfer.hpp"

namespace ptnet::cli::cmd_har_bench {
namespace {

struct HarBenchCli {
  ptnet::har::BenchOptions o;  // the library's defaults
  std::string bands = ptnet::join(o.deployment_bands, ",");
  std::string syntheses = ptnet::join(o.syntheses, ",");
  std::string activities;
  std::string model, training_set, out = "har-bench";
  int training_bodies = 24;
  int transfer_stride = 15;
  int threads = 2;
  bool force = false;
};

void run(HarBenchCli& c) {
  namespace fs = std::filesystem;
  ptnet::har::BenchOptions& o = c.o;
  o.deployment_bands = ptnet::split_list(c.bands);
  o.syntheses = ptnet::split_list(c.syntheses);
  o.activities = ptnet::split_list(c.activities);
  o.classifier.threads = c.threads;
  if (!ptnet::cli::globals().quiet) o.progress = ptnet::cli::print;

  if (!c.training_set.empty()) {
    ptnet::har::write_bench_training_set(c.training_set, o, c.training_bodies, c.force);
    std::cout << "wrote " << c.training_set << "; train the transfer model on it, for instance\n  ptnet train --data "
              << c.training_set << " --out hb_model --preset fast\n";
    return;
  }
  ptnet::check_outputs_in_folder(c.out, {"results.json", "index.html", "f1.svg"}, c.force);
  const auto path = [&](const std::string& name) { return (fs::path(c.out) / name).string(); };

  std::optional<ptnet::Transfer> transfer;
  ptnet::har::TransferFn fn;
  if (!c.model.empty()) {
    ptnet::TransferOptions to;
    to.stride = c.transfer_stride;
    to.threads = c.threads;  // torch::set_num_threads: the classifiers too
    transfer.emplace(c.model, to);
    fn = [&](const ptnet::PressureSequence& s, const ptnet::BodySpec& from, const ptnet::BodySpec& to_body) {
      return transfer->run(s, from, to_body);
    };
  }
  const ptnet::har::BenchResult r = ptnet::har::run_bench(o, fn);
  ptnet::make_folder(c.out);
  ptnet::write_text_file(path("results.json"), ptnet::har::bench_json(r), c.force);
  const std::string page = ptnet::har::write_bench_report(c.out, r, c.force).back();
  std::cout << ptnet::har::format_bench(r);
  std::cout << "Time: " << ptnet::fixed_text(r.seconds, 1) << " s (simulation " << ptnet::fixed_text(r.simulate_seconds, 1)
            << ", synthesis " << ptnet::fixed_text(r.transfer_seconds, 1) << ", classifiers "
            << ptnet::fixed_text(r.classify_seconds, 1) << ")\n";
  std::cout << "wrote " << path("results.json") << "; open " << page << " in a browser\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<HarBenchCli>();
  CLI::App* s = app.add_subcommand(
      "har-bench",
      "Body-shift HAR benchmark: a classifier trained on recorded bodies (band mid) plus the deployment bodies' "
      "windows synthesised per source (model, copy, weight ratio, body scale; oracle = simulated directly), scored "
      "on the deployment bodies' held-out test parts");
  s->add_option("--mocap", c->o.mocap, "Folder with clips.csv (activity column) and BVH files; default: procedural clips")
      ->check(CLI::ExistingDirectory);
  auto* model = s->add_option("--model", c->model, "Trained transfer model folder (for the sources model, model-mean)")
                    ->check(CLI::ExistingDirectory);
  s->add_option("--model-data", c->o.model_data,
                "The model's training set (--write-training-set's output): checked to hold no test part")
      ->check(CLI::ExistingFile)
      ->needs(model);
  s->add_option("--write-training-set", c->training_set,
                "Only write the transfer model's training set (the clips' training parts on bodies of band all) "
                "to this .h5, then stop")
      ->excludes(model);
  s->add_option("--training-bodies", c->training_bodies, "Bodies of the training set (band all)")
      ->capture_default_str()
      ->check(CLI::Range(2, 1000));
  s->add_option("--syntheses", c->syntheses,
                "Training sources besides recorded and oracle: model, model-mean, copy, weight-ratio, body-scale, "
                "body-scale-read")
      ->capture_default_str();
  s->add_option("--deployment-bands", c->bands,
                "Deployment populations: " + ptnet::join(ptnet::har::deployment_band_names(), ", ") +
                    " (docs/har_bench.md)")
      ->capture_default_str();
  s->add_option("--activities", c->activities, "Comma-separated activities (default: every one with a usable clip)");
  s->add_option("--recorded-bodies", c->o.recorded_bodies, "Recorded bodies (band mid)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  s->add_option("--bodies-per-band", c->o.bodies_per_band, "Deployment bodies per band")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  s->add_option("--runs", c->o.runs, "Seeded runs per source and label kind")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  s->add_option("--ensemble", c->o.ensemble, "Classifiers per run, their probabilities averaged")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  s->add_option("--stride", c->o.stride, "Frames between window starts")->capture_default_str()->check(CLI::Range(1, 30));
  s->add_option("--pool", c->o.input.pool, "Classifier input: cells averaged per side (2: 4 cm cells)")
      ->capture_default_str()
      ->check(CLI::Range(1, 8));
  s->add_option("--epochs", c->o.classifier.epochs, "Classifier training epochs")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  s->add_option("--performers", c->o.performers, "Procedural performers (without --mocap)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  s->add_option("--seconds", c->o.seconds, "Procedural clip length (without --mocap)")
      ->capture_default_str()
      ->check(ptnet::cli::in_range(4, 600));
  s->add_option("--seed", c->o.seed, "Seed of the bodies, sensor and procedural motions; classifier run r uses seed + r - 1")
      ->capture_default_str();
  s->add_option("--transfer-stride", c->transfer_stride, "Frames between the model's windows (1-30)")
      ->capture_default_str()
      ->check(CLI::Range(1, 30));
  s->add_option("--threads", c->threads, "LibTorch threads of the transfer (and of the classifiers with --workers 1)")
      ->capture_default_str()
      ->check(ptnet::cli::thread_count(false));
  s->add_option("--workers", c->o.workers,
                "Classifiers trained at once, one LibTorch thread each (0: one per core); the same result as "
                "--workers 1 --threads 1")
      ->capture_default_str()
      ->check(ptnet::cli::thread_count(true));
  s->add_flag("--pseudo", c->o.pseudo_labels,
              "Add a second table: the paper's mean-shift pseudo labels (doubles the classifiers)");
  s->add_option("--out", c->out, "Output folder (results.json, index.html, f1.svg)")->capture_default_str();
  s->add_flag("--force", c->force, "Overwrite existing outputs");
  s->callback([c] { run(*c); });
}

}  // namespace

PTNET_COMMAND(72, setup);
}  // namespace ptnet::cli::cmd_har_bench
