// ptnet import: real recordings (.npy / .csv frames per subject, listed in a
// manifest CSV) into the dataset format, ready for validate-har. Thin glue
// over ptnet::har::import_recordings (docs/har.md).
#if defined(PTNET_HAR_IMPORT)
#include "command.hpp"
#include "ptnet/har.hpp"

namespace {

struct ImportCommand {
  std::string manifest, out;
  ptnet::har::ImportOptions o;
  bool force = false;
};

void setup(CLI::App& app) {
  auto c = std::make_shared<ImportCommand>();
  CLI::App* s = app.add_subcommand(
      "import",
      "Import real pressure-mat recordings into a dataset file: a manifest CSV "
      "subject,sex,height_cm,weight_kg,file[,category], each file a float32 .npy [T, rows, cols] "
      "or a .csv of one frame per line (kPa)");
  s->add_option("--manifest", c->manifest, "Manifest CSV")->required()->check(CLI::ExistingFile);
  s->add_option("--out", c->out, "Dataset file to write (.h5)")->required();
  s->add_option("--rows", c->o.mat.rows, "Mat rows")->capture_default_str()->check(CLI::Range(1, 4096));
  s->add_option("--cols", c->o.mat.cols, "Mat columns")->capture_default_str()->check(CLI::Range(1, 4096));
  s->add_option("--pitch", c->o.mat.pitch_m, "Cell size (m)")->capture_default_str()->check(CLI::PositiveNumber);
  s->add_option("--fps", c->o.fps, "Frame rate of the recordings (Hz)")->capture_default_str()->check(CLI::PositiveNumber);
  s->add_flag("--force", c->force, "Overwrite an existing file");
  s->callback([c] { ptnet::har::import_recordings(c->manifest, c->out, c->o, c->force); });
}

}  // namespace

PTNET_COMMAND(68, setup);
#endif
