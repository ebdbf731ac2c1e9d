// ptnet simulate: motion clips x bodies -> pressure-mat dataset (HDF5).
//
//   ptnet simulate --motions mocap --clips mocap/clips.csv
//                  --bodies bodies.csv --out mocap.h5
//   ptnet simulate --embedded --performers 2 --takes 1 --seconds 4 --bodies bodies.csv --out demo.h5
//
// Options and sensor defaults: docs/simulate.md.
#include <malloc.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <tuple>

#include "command.hpp"
#include "ptnet/body_spec.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace ptnet::cli::cmd_simulate {
namespace {

// simulate_dataset allocates each chunk's sequences (MBs each) and frees them
// once written: glibc would hand those pages back to the kernel and fault
// them in again for the next chunk (a tenth of the run's CPU in page faults).
// This process keeps freed memory for reuse instead; the command's choice, not
// the library's (it is process-wide, and the Python module shares it).
void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest: sequences come from the heap
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // and stay there when freed
#endif
}

struct SimulateCli {
  std::vector<std::string> motions;
  std::string clips, bodies, out;
  bool embedded = false;
  EmbeddedCorpus corpus;
  SimulateDatasetOptions dataset;  // fps, seed, threads, compression, force (sim: from `sim` below)
  SimSettings sim;
  std::string units = "auto", up = "y";
  std::string marker_map;
  bool no_floor = false;
  std::string shard;  // "K/N"
  std::vector<double> speeds;  // empty: each clip once, as recorded
};

void run(const SimulateCli& c) {
  const bool quiet = globals().quiet;
  if (c.embedded && (!c.motions.empty() || !c.clips.empty()))
    throw Error("simulate: --embedded replaces --motions and --clips; give one or the other");
  if (!c.embedded && c.motions.empty() && c.clips.empty())
    throw Error("simulate: give --motions (BVH files or folders), --clips, or --embedded");

  SimulateDatasetOptions o = c.dataset;
  o.noise_floor = !c.no_floor;
  o.generator = std::string("ptnet ") + PTNET_VERSION + " simulate";
  if (!c.shard.empty() && !parse_shard(c.shard, o.shard_index, o.shard_count))
    throw Error("--shard: expected K/N with 0 <= K < N (e.g. 0/4), found " + escaped(c.shard));
  o.sim = sim_options(c.sim);

  // Inputs are all checked before any work: output path, bodies, clips.
  check_output_path(c.out, o.force);
  const std::vector<BodySpec> bodies = read_bodies_csv(c.bodies);
  if (bodies.empty()) throw Error::in(c.bodies, "no bodies (expected at least one row after the header)");
  std::vector<ClipSource> clips;
  if (c.embedded) {
    clips = embedded_clips(c.corpus.performers, c.corpus.takes, c.corpus.seconds, o.seed, o.fps);
  } else {
    MotionOptions mo;
    mo.units = parse_units(c.units);
    mo.up = parse_up_axis(c.up);
    mo.fps = o.fps;
    mo.marker_map = c.marker_map;
    clips = clips_from_files(c.motions, c.clips, mo);
  }
  if (!c.speeds.empty()) clips = clips_at_speeds(clips, c.speeds);
  if (!quiet)
    std::cerr << "simulate: " << clips.size() << " clips x " << bodies.size() << " bodies = "
              << clips.size() * bodies.size() << " sequences"
              << (o.shard_count > 1 ? ", shard " + c.shard : std::string()) << "\n";
  o.progress = print;
  keep_freed_memory();
  const SimulateDatasetSummary r = simulate_dataset(clips, bodies, c.out, o);
  if (!quiet) {
    std::fprintf(stderr, "simulate: %d sequences, %lld frames in %.1f s (%.0f frames/s)\n", r.sequences,
                 r.frames, r.seconds, r.seconds > 0 ? double(r.frames) / r.seconds : 0.0);
  }
  std::cout << "wrote " << c.out << "\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<SimulateCli>();
  auto* cmd = app.add_subcommand(
      "simulate",
      "Simulate every motion clip on every body (retargeted onto the body's height) on a\n"
      "pressure mat and write the HDF5 dataset (docs/formats.md; options: docs/simulate.md).");
  cmd->add_option("--motions", c->motions, "BVH or marker (.trc, .c3d) files, or folders (searched recursively for them)");
  cmd->add_option("--clips", c->clips,
                  "Clips CSV (file,subject,category,take[,metres_per_unit,up,marker_map,static]); alone: every clip it lists");
  cmd->add_flag("--embedded", c->embedded, "Procedural motions (as ptnet demo) instead of BVH files");
  cmd->add_option("--bodies", c->bodies, "Bodies CSV (id,sex,height_cm,weight_kg[,role])")->required();
  cmd->add_option("-o,--out", c->out, "Output dataset (.h5)")->required();
  const EmbeddedCorpusRanges& er = kEmbeddedCorpusRanges;
  cmd->add_option("--performers", c->corpus.performers, "--embedded: procedural performers")
      ->capture_default_str()->check(int_range(er.performers));
  cmd->add_option("--takes", c->corpus.takes, "--embedded: takes per performer and category")
      ->capture_default_str()->check(int_range(er.takes));
  cmd->add_option("--seconds", c->corpus.seconds, "--embedded: seconds per clip")
      ->capture_default_str()->check(in_range(er.seconds));
  cmd->add_option("--fps", c->dataset.fps, "Frame rate of the dataset (motions are resampled)")
      ->capture_default_str()->check(in_range(kFpsRange));
  cmd->add_option("--seed", c->dataset.seed, "Seed of the sensor noise (and of --embedded motions)")->capture_default_str();
  cmd->add_option("--threads", c->dataset.threads, "Threads (0: all cores)")->capture_default_str()->check(thread_count(true));
  cmd->add_option("--placement", c->sim.placement, "fixed: a physical mat; follow: the mat follows the body")
      ->capture_default_str()->check(CLI::IsMember({"fixed", "follow"}));
  cmd->add_option("--units", c->units, "BVH units for files the clips CSV does not describe: auto|m|cm|mm|in|cmu")
      ->capture_default_str();
  cmd->add_option("--up", c->up, "BVH up axis for files the clips CSV does not describe: y|z")->capture_default_str();
  const SimSettingsRanges& r = kSimSettingsRanges;
  const SensorModel sensor;
  cmd->add_option("--rows", c->sim.rows, "Mat rows (along the walking axis)")->capture_default_str()->check(int_range(r.rows));
  cmd->add_option("--cols", c->sim.cols, "Mat columns")->capture_default_str()->check(int_range(r.cols));
  cmd->add_option("--pitch", c->sim.pitch_m, "Cell size (m)")->capture_default_str()->check(in_range(r.pitch_m));
  cmd->add_option("--compliance-mm", c->sim.compliance_mm, "Contact band above the ground (mm)")
      ->capture_default_str()->check(in_range(r.compliance_mm));
  cmd->add_option("--subsamples", c->sim.subsamples, "Depth samples per cell side")
      ->capture_default_str()->check(int_range(r.subsamples));
  cmd->add_option("--forces", c->dataset.forces_dir,
                  "Also write each sequence's simulated ground reaction (total and per foot, N and body weights,\n"
                  "CoP along the foot) into this folder as NAME.mot (OpenSim storage) or NAME.csv");
  add_table_format(cmd, "--forces-format", c->dataset.forces_format, "mot or csv");
  cmd->add_option("--marker-map", c->marker_map,
                  ".trc files the clips CSV does not describe: a shipped marker map (delaware, plugin-gait, common)\n"
                  "or a map file (default: the shipped map that places the file)");
  cmd->add_flag("--ideal-sensor", c->sim.ideal_sensor, "No crosstalk, saturation, noise, threshold or quantisation");
  const auto sensor_default = [](double v) { return " (default " + number_text(v) + ")"; };
  cmd->add_option("--crosstalk", c->sim.crosstalk, "Fraction leaking to each of 4 neighbours" + sensor_default(sensor.crosstalk))
      ->check(in_range(r.crosstalk));
  cmd->add_option("--saturation-kpa", c->sim.saturation_kpa, "Readings clip here" + sensor_default(sensor.saturation_kpa))
      ->check(in_range(r.saturation_kpa));
  cmd->add_option("--noise-kpa", c->sim.noise_kpa, "Read noise SD" + sensor_default(sensor.noise_sd_kpa))
      ->check(in_range(r.noise_kpa));
  cmd->add_option("--threshold-kpa", c->sim.threshold_kpa, "Activation threshold" + sensor_default(sensor.threshold_kpa))
      ->check(in_range(r.threshold_kpa));
  cmd->add_option("--quantum-kpa", c->sim.quantum_kpa, "ADC step, 0: off" + sensor_default(sensor.quantum_kpa))
      ->check(in_range(r.quantum_kpa));
  cmd->add_option("--speeds", c->speeds,
                  "Comma-separated playback speeds, e.g. 0.8,1,1.25: every clip again at each, re-simulated "
                  "(a faster or slower motion; ids get _x0.8), to augment a training set")
      ->delimiter(',')
      ->check(in_range(kClipSpeedRange));
  cmd->add_flag("--no-floor", c->no_floor,
                "Skip the second-seed copies of original-body sequences (/floor: the noise floor of evaluate)");
  cmd->add_option("--shard", c->shard,
                  "K/N: only the K-th (0-based) of N contiguous blocks of the clip x body list; "
                  "ptnet merge joins the N files (docs/distributed.md)");
  cmd->add_option("--compression", c->dataset.compression,
                  "Deflate level of the sequences: 1 codes zero runs only (fastest, smallest on "
                  "sparse mats), 2-9 general deflate, 0 none (largest)")
      ->capture_default_str()
      ->check(CLI::Range(0, 9));
  cmd->add_flag("-f,--force", c->dataset.force, "Overwrite the output if it exists");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(40, setup);
}  // namespace ptnet::cli::cmd_simulate
