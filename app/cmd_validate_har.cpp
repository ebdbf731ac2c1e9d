// ptnet validate-har: does transferred data help an activity classifier?
// (paper section 4.2, Table 3; docs/har.md). Thin glue over ptnet/har.hpp
// and ptnet/transfer.hpp.
#include <filesystem>
#include <iostream>
#include <sstream>

#include "command.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/har.hpp"
#include "ptnet/io.hpp"
#include "ptnet/model_config.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/transfer.hpp"

namespace ptnet::cli::cmd_validate_har {
namespace {

struct ValidateHarCli {
  std::string real, model, baseline, bodies, out = "har";
  std::string train_subjects = "1,2,3", test_subjects = "4,5";
  int runs = 10;
  int stride = 5;
  int synthetic_bodies = ptnet::har::HarOptions{}.synthetic_bodies;
  int transfer_stride = 15;
  int threads = 1;
  int pca = 4;
  int epochs = ptnet::har::ClassifierOptions{}.epochs;
  double bandwidth = 0;
  std::uint64_t seed = 1;
  std::string device = "cpu";
  bool no_categories = false;
  bool force = false;
};

std::vector<std::string> subject_list(const std::string& text, const std::string& option) {
  std::vector<std::string> out = ptnet::split_list(text);
  if (out.empty()) throw ptnet::Error(option + ": no subjects given");
  return out;
}

void write_outputs(const ValidateHarCli& o, const ptnet::har::HarResult& r,
                   const std::string& json_path, const std::string& png_path) {
  ptnet::make_folder(o.out);
  ptnet::write_text_file(json_path, ptnet::har::to_json(r), o.force);
  ptnet::har::write_confusion_png(png_path, r, o.force);
  const std::string page = ptnet::har::write_html_report(o.out, r, o.force).back();
  std::cout << ptnet::har::format_table(r);
  if (!ptnet::cli::globals().quiet)
    std::cerr << "validate-har: wrote " << json_path << ", " << png_path << " and " << page << "\n";
  std::cout << "open " << page << " in a browser: the report on one page\n";
}

void run(const ValidateHarCli& o) {
  namespace fs = std::filesystem;
  const bool quiet = ptnet::cli::globals().quiet;
  ptnet::har::HarOptions h;
  h.train_subjects = subject_list(o.train_subjects, "--train-subjects");
  h.test_subjects = subject_list(o.test_subjects, "--test-subjects");
  h.runs = o.runs;
  h.stride = o.stride;
  h.pca_components = o.pca;
  h.mean_shift.bandwidth = o.bandwidth;
  h.classifier.epochs = o.epochs;
  h.classifier.device = o.device;
  h.classifier.seed = o.seed;
  h.seed = o.seed;
  h.synthetic_bodies = o.synthetic_bodies;
  h.category_labels = !o.no_categories;
  if (!o.bodies.empty()) h.bodies = ptnet::read_bodies_csv(o.bodies);
  if (!quiet) h.progress = ptnet::cli::print;

  // Outputs are checked before hours of work, not after.
  ptnet::check_outputs_in_folder(o.out, {"results.json", "confusion.png", "index.html"}, o.force);
  const std::string json_path = (fs::path(o.out) / "results.json").string();
  const std::string png_path = (fs::path(o.out) / "confusion.png").string();
  const std::string page_path = (fs::path(o.out) / "index.html").string();

  ptnet::Dataset real = ptnet::Dataset::open(o.real);
  ptnet::har::check_subjects(real, h);  // before loading anything else
  if (o.model.empty() == o.baseline.empty())
    throw ptnet::Error("validate-har: give --model (a trained model) or --baseline (copy | weight-ratio)");
  if (!o.baseline.empty()) {
    // Reference points without a model: synthetic = the source unchanged
    // (more of the same data) or scaled by the weight ratio (eval's baselines).
    if (o.baseline != "copy" && o.baseline != "weight-ratio")
      throw ptnet::Error("--baseline: expected copy or weight-ratio, found '" + o.baseline + "'");
    const bool copy = o.baseline == "copy";
    if (!quiet)
      std::cerr << "validate-har: real " << o.real << ", baseline " << o.baseline << " instead of a model\n";
    const ptnet::har::HarResult r = ptnet::har::validate_har(
        real,
        [copy](const ptnet::PressureSequence& s, const ptnet::BodySpec& from, const ptnet::BodySpec& to_body) {
          return copy ? ptnet::copy_baseline(s)
                      : ptnet::weight_ratio_baseline(s, from.weight_kg, to_body.weight_kg);
        },
        h);
    write_outputs(o, r, json_path, png_path);
    return;
  }
  const ptnet::ModelDir dir = ptnet::read_model_dir(o.model);
  const ptnet::MatSpec& mm = dir.mat;
  const ptnet::MatSpec& dm = real.info().mat;
  if (!(mm == dm)) {
    std::ostringstream s;
    s << "model mat " << mm.rows << "x" << mm.cols << " (" << mm.pitch_m << " m) differs from "
      << o.real << "'s " << dm.rows << "x" << dm.cols << " (" << dm.pitch_m << " m)";
    throw ptnet::Error::in(ptnet::ModelFiles(o.model).config(), s.str());
  }
  ptnet::TransferOptions to;
  to.stride = o.transfer_stride;
  to.device = o.device;
  to.threads = o.threads;  // torch::set_num_threads: the classifiers too
  ptnet::Transfer transfer(o.model, to);
  if (!quiet)
    std::cerr << "validate-har: real " << o.real << ", model " << o.model << ", train "
              << o.train_subjects << ", test " << o.test_subjects << ", runs " << o.runs
              << ", stride " << o.stride << ", transfer stride " << o.transfer_stride << ", threads "
              << o.threads << "\n";

  const ptnet::har::HarResult r = ptnet::har::validate_har(
      real,
      [&](const ptnet::PressureSequence& s, const ptnet::BodySpec& from,
          const ptnet::BodySpec& to_body) { return transfer.run(s, from, to_body); },
      h);

  write_outputs(o, r, json_path, png_path);
}

void setup(CLI::App& app) {
  auto o = std::make_shared<ValidateHarCli>();
  CLI::App* c = app.add_subcommand(
      "validate-har",
      "HAR validation (paper Table 3): mean-shift pseudo labels on real windows, a CNN trained on "
      "real, synthetic (transferred) and real+synthetic windows of the training subjects, macro "
      "F1 on the test subjects over seeded runs");
  c->add_option("--real", o->real, "Real recordings (ptnet dataset .h5); subjects = its bodies")
      ->required()
      ->check(CLI::ExistingFile);
  auto* model = c->add_option("--model", o->model, "Trained model folder (config.json + model.pt)")
                    ->check(CLI::ExistingDirectory);
  c->add_option("--baseline", o->baseline,
                "Instead of --model: synthetic windows from a naive baseline, copy (the source "
                "unchanged) or weight-ratio (scaled by target/source weight), as reference points")
      ->excludes(model);
  c->add_option("--train-subjects", o->train_subjects,
                "Comma-separated body ids (\"1\" also matches s1 / subject1)")
      ->capture_default_str();
  c->add_option("--test-subjects", o->test_subjects, "Comma-separated body ids, disjoint from train")
      ->capture_default_str();
  c->add_option("--runs", o->runs, "Seeded classifier runs per training source")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  c->add_option("--bodies", o->bodies,
                "Synthetic target bodies CSV (id,sex,height_cm,weight_kg); default: sampled like "
                "the paper");
  c->add_option("--synthetic-bodies", o->synthetic_bodies,
                "Bodies to sample when --bodies is not given")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  c->add_option("--bandwidth", o->bandwidth,
                "Mean-shift bandwidth in PCA units (default: estimated, docs/har.md)")
      ->check(ptnet::cli::positive(1e6));
  c->add_option("--stride", o->stride, "Frames between window starts (paper: 1)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  c->add_option("--transfer-stride", o->transfer_stride,
                "Frames between the model's windows when transferring (1-30)")
      ->capture_default_str()
      ->check(CLI::Range(1, 30));
  c->add_option("--pca", o->pca, "PCA components of the clustering features")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  c->add_option("--epochs", o->epochs, "Classifier training epochs")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  c->add_option("--seed", o->seed, "Seed of run 1 (run r uses seed + r - 1) and of body sampling")
      ->capture_default_str();
  c->add_option("--device", o->device, "cpu | cuda | cuda:N")->capture_default_str();
  c->add_option("--threads", o->threads,
                "CPU threads of the transfer model and the classifiers (1: measured fastest for "
                "these small networks, docs/results.md)")
      ->capture_default_str()
      ->check(ptnet::cli::thread_count(false));
  c->add_flag("--no-categories", o->no_categories,
              "Skip the classifiers trained on the dataset's category labels");
  c->add_option("--out", o->out, "Output folder (results.json, confusion.png, index.html)")
      ->capture_default_str();
  c->add_flag("--force", o->force, "Overwrite existing outputs");
  c->callback([o] { run(*o); });
}

}  // namespace

PTNET_COMMAND(70, setup);
}  // namespace ptnet::cli::cmd_validate_har
