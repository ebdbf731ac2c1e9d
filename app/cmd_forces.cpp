// ptnet forces: what a dataset's mat reads as a force plate would, per
// sequence and frame (vertical force, centre of pressure, contact area), as
// OpenSim storage (.mot) or CSV files.
#include <cstdio>
#include <memory>

#include "command.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"

namespace ptnet::cli::cmd_forces {
namespace {

struct ForcesCli {
  std::string dataset;
  std::vector<std::string> sequences;
  std::string out;
  ptnet::TableFormat format = ptnet::TableFormat::mot;
  double contact_kpa = ptnet::kContactKpa;
  bool force = false;
};

void run(const ForcesCli& o) {
  const ptnet::Dataset d = ptnet::Dataset::open(o.dataset);
  const auto written = ptnet::write_mat_forces(d, o.sequences, o.out, o.format, o.force, o.contact_kpa);
  if (!ptnet::cli::globals().quiet)
    std::fprintf(stderr, "forces: wrote %zu file%s to %s\n", written.size(), written.size() == 1 ? "" : "s",
                 o.out.c_str());
}

void setup(CLI::App& app) {
  auto o = std::make_shared<ForcesCli>();
  auto* cmd = app.add_subcommand(
      "forces",
      "Write what each sequence's mat reads, as a force plate under it would: per frame the\n"
      "vertical force (N and body weights of the sequence's body), its centre of pressure in\n"
      "the mat's frame (m from the mat's centre, x towards row 0, y towards column 0) and the\n"
      "contact area, one OpenSim storage (.mot) or CSV file per sequence. Any dataset: simulated,\n"
      "transferred (ptnet transfer --out x.h5) or imported recordings. The mat reads only what\n"
      "stands on it; for the simulator's whole ground reaction, per foot, see simulate --forces.");
  cmd->add_option("dataset", o->dataset, "Dataset file (.h5)")->required();
  cmd->add_option("-s,--sequence", o->sequences, "Sequence (repeat for several; default: every sequence)");
  cmd->add_option("-o,--out", o->out, "Output folder: one <sequence>.<format> per sequence")->required();
  ptnet::cli::add_table_format(cmd, "--format", o->format, "mot (OpenSim storage) or csv");
  cmd->add_option("--contact", o->contact_kpa, "Contact area: cells above this many kPa")
      ->capture_default_str()
      ->check(ptnet::cli::in_range(ptnet::kPressureRangeKpa));
  cmd->add_flag("-f,--force", o->force, "Overwrite existing output files");
  cmd->callback([o] { run(*o); });
}

}  // namespace

PTNET_COMMAND(62, setup);
}  // namespace ptnet::cli::cmd_forces
