// ptnet render: heatmap figures of dataset sequences (PNG strip or GIF).
#include <memory>

#include "command.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/viz.hpp"

namespace ptnet::cli::cmd_render {
namespace {

struct RenderCli {
  std::string dataset;
  std::vector<std::string> sequences;
  std::string out;
  ptnet::FigureOptions figure;
  bool force = false;
};

void run(const RenderCli& o) {
  ptnet::Dataset d = ptnet::Dataset::open(o.dataset);
  ptnet::render_figure(d, o.sequences, o.out, o.figure, o.force);
  if (!ptnet::cli::globals().quiet) std::fprintf(stderr, "render: wrote %s\n", o.out.c_str());
}

void setup(CLI::App& app) {
  auto o = std::make_shared<RenderCli>();
  auto* cmd = app.add_subcommand(
      "render",
      "Draw pressure heatmaps of dataset sequences: a PNG strip of frames (one row per\n"
      "sequence) or an animated GIF at the sequence's frame rate (sequences side by side).\n"
      "Viridis colours on one shared kPa scale; the mat's far end (row 0) at the top, the\n"
      "walker's left (col 0) on the left.");
  cmd->add_option("dataset", o->dataset, "Dataset file (.h5)")->required();
  cmd->add_option("-s,--sequence", o->sequences, "Sequence to draw (repeat for several; `ptnet info` lists them)")
      ->required();
  cmd->add_option("-o,--out", o->out, "Output figure: .png (strip) or .gif (animation)")->required();
  cmd->add_option("--frames", o->figure.frames, "Number of evenly spaced frames (PNG default 6; GIF default all)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--frame-list", o->figure.frame_list, "Explicit frame indices, e.g. 0,10,20")
      ->delimiter(',')
      ->check(CLI::Range(0, 2147483647))
      ->excludes("--frames");
  cmd->add_flag("--cop", o->figure.cop, "Draw the centre-of-pressure trace");
  cmd->add_option("--vmax", o->figure.vmax_kpa, "Top of the colour scale in kPa (default: data maximum, rounded up)")
      ->check(ptnet::cli::positive(1e9));
  cmd->add_option("--cell-px", o->figure.cell_px, "Pixels per mat cell")->capture_default_str()->check(CLI::Range(1, 40));
  cmd->add_flag("-f,--force", o->force, "Overwrite the output if it exists");
  cmd->callback([o] { run(*o); });
}

}  // namespace

PTNET_COMMAND(60, setup);
}  // namespace ptnet::cli::cmd_render
