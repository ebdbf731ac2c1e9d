// ptnet standin: writes the stand-in for real pressure-mat recordings (five
// procedural subjects, or one per CMU subject of a mocap folder, on their own
// bodies, a degraded sensor; docs/har.md). Thin glue
// over ptnet::har::write_standin.
#include <iostream>

#include "command.hpp"
#include "ptnet/har.hpp"

namespace ptnet::cli::cmd_standin {
namespace {

struct StandinCli {
  std::string out;
  bool force = false;
  ptnet::har::StandinOptions o;
};

void setup(CLI::App& app) {
  auto c = std::make_shared<StandinCli>();
  CLI::App* s = app.add_subcommand(
      "standin",
      "Write the STAND-IN for real recordings (simulated, not real data): N subjects, each its "
      "own body and procedural performer, every category (or, with --mocap, one subject per CMU "
      "subject of a mocap folder), a noisier sensor with crosstalk, per-cell gain spread and dead "
      "cells (input for validate-har)");
  s->add_option("--out", c->out, "Dataset file to write (.h5)")->required();
  auto* mocap = s->add_option("--mocap", c->o.mocap,
                              "Mocap folder (clips.csv + BVH): one subject s<N> per CMU subject N, "
                              "its clips retargeted onto its own sampled body, instead of the "
                              "procedural performers")
                    ->check(CLI::ExistingDirectory);
  s->add_option("--subjects", c->o.subjects, "Subjects s1..sN (procedural)")
      ->capture_default_str()
      ->check(CLI::Range(2, 50))
      ->excludes(mocap);
  s->add_option("--seconds", c->o.seconds, "Seconds per category clip (procedural)")
      ->capture_default_str()
      ->check(ptnet::cli::in_range(2, 600))
      ->excludes(mocap);
  s->add_option("--takes", c->o.takes, "Clips per category and subject (procedural)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10))
      ->excludes(mocap);
  s->add_option("--first-performer", c->o.first_performer, "Procedural performer of s1")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000))
      ->excludes(mocap);
  s->add_option("--crosstalk", c->o.crosstalk, "Crosstalk per neighbour")->capture_default_str()->check(ptnet::cli::in_range(0, 0.2));
  s->add_option("--noise", c->o.noise_sd_kpa, "Read noise sd (kPa)")->capture_default_str()->check(ptnet::cli::in_range(0, 50));
  s->add_option("--gain-sd", c->o.gain_sd, "Sigma of the per-cell log-normal gain")->capture_default_str()->check(ptnet::cli::in_range(0, 1));
  s->add_option("--dead", c->o.dead_fraction, "Fraction of dead cells")->capture_default_str()->check(ptnet::cli::in_range(0, 0.5));
  s->add_option("--placement", c->o.placement,
                "fixed: a physical 1.6 m mat; follow: the mat follows the body (real clips that walk "
                "or leap off a fixed mat, docs/har.md)")
      ->capture_default_str()
      ->check(CLI::IsMember({"fixed", "follow"}));
  s->add_option("--seed", c->o.seed, "Seed (bodies, motions, noise, gain map)")->capture_default_str();
  s->add_option("--threads", c->o.threads, "Simulation threads (0: all cores)")
      ->capture_default_str()
      ->check(ptnet::cli::thread_count(true));
  s->add_flag("--force", c->force, "Overwrite an existing file");
  s->callback([c] {
    if (!ptnet::cli::globals().quiet)
      c->o.progress = ptnet::cli::print;
    ptnet::har::write_standin(c->out, c->o, c->force);
  });
}

}  // namespace

PTNET_COMMAND(69, setup);
}  // namespace ptnet::cli::cmd_standin
