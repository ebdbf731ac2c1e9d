// ptnet import: real recordings (.npy / .csv frames per subject, listed in a
// manifest CSV) into the dataset format, ready for validate-har; or, with
// --dataset, the training subjects of such a dataset as a fine-tuning set for
// `ptnet train --init`. Thin glue over ptnet::har::import_recordings and
// ptnet::har::write_finetune_set (docs/har.md).
#include <sstream>

#include "command.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::cli::cmd_import {
namespace {

struct ImportCli {
  std::string manifest, dataset, subjects, out;
  ptnet::har::ImportOptions o;
  bool force = false;
};

void setup(CLI::App& app) {
  auto c = std::make_shared<ImportCli>();
  CLI::App* s = app.add_subcommand(
      "import",
      "Import real pressure-mat recordings into a dataset file: a manifest CSV "
      "subject,sex,height_cm,weight_kg,file[,category], each file a float32 .npy [T, rows, cols] "
      "or a .csv of one frame per line (kPa). With --dataset and --subjects: write those "
      "(training) subjects of a dataset as a fine-tuning set for `ptnet train --init MODEL "
      "--identity-pairs` (bodies role retargeted, take 1; no other subject is copied)");
  auto* manifest = s->add_option("--manifest", c->manifest, "Manifest CSV")->check(CLI::ExistingFile);
  auto* dataset = s->add_option("--dataset", c->dataset, "A dataset of real recordings (.h5) to take "
                                "the fine-tuning subjects from")
                      ->check(CLI::ExistingFile)
                      ->excludes(manifest);
  s->add_option("--subjects", c->subjects,
                "With --dataset: comma-separated subjects to copy (the training subjects; \"1\" "
                "also matches s1 / subject1)")
      ->needs(dataset);
  s->add_option("--out", c->out, "Dataset file to write (.h5)")->required();
  s->add_option("--rows", c->o.mat.rows, "Mat rows")->capture_default_str()->check(CLI::Range(1, 4096));
  s->add_option("--cols", c->o.mat.cols, "Mat columns")->capture_default_str()->check(CLI::Range(1, 4096));
  s->add_option("--pitch", c->o.mat.pitch_m, "Cell size (m)")->capture_default_str()->check(ptnet::cli::positive(10));
  s->add_option("--fps", c->o.fps, "Frame rate of the recordings (Hz)")->capture_default_str()->check(ptnet::cli::positive(10000));
  s->add_flag("--force", c->force, "Overwrite an existing file");
  s->callback([c] {
    if (!c->dataset.empty()) {
      if (c->subjects.empty()) throw ptnet::Error("--dataset needs --subjects (the training subjects)");
      ptnet::har::write_finetune_set(c->dataset, ptnet::split_list(c->subjects), c->out, c->force);
    } else if (!c->manifest.empty()) {
      ptnet::har::import_recordings(c->manifest, c->out, c->o, c->force);
    } else {
      throw ptnet::Error("import: give --manifest (recordings) or --dataset with --subjects");
    }
  });
}

}  // namespace

PTNET_COMMAND(68, setup);
}  // namespace ptnet::cli::cmd_import
