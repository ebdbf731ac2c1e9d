// ptnet physics-bench: the simulator against real force plates.
//
//   ptnet physics-bench --trials bench/real-gait.csv --data real-gait --out physics
//
// Each trial of the trials CSV (its columns: kGaitTrialColumns,
// docs/physics.md) is simulated on a body
// of the subject's sex, stature and mass; its vertical force, contacts and
// centre of pressure are set beside the plates' and the naive reference's.
// Writes OUT/results.json, OUT/index.html and OUT/<trial>_sim.mot; prints
// the table.
#include <cstdio>
#include <iostream>
#include <memory>

#include "command.hpp"
#include "ptnet/error.hpp"
#include "ptnet/plates.hpp"

namespace ptnet::cli::cmd_physics_bench {
namespace {

struct PhysicsBenchCli {
  std::string trials, data, out;
  double fps = 0;
  bool force = false;
};

std::string figure(double v, int digits) { return std::isfinite(v) ? fixed_text(v, digits) : "-"; }

void run(const PhysicsBenchCli& c) {
  const std::vector<GaitTrial> trials = read_gait_trials(c.trials, c.data);
  check_physics_report(trials, c.out, c.force);  // before any trial runs
  PhysicsBenchOptions o;
  o.fps = c.fps;
  std::vector<GaitTrialResult> results;
  for (const GaitTrial& t : trials) {
    if (!globals().quiet) std::fprintf(stderr, "physics-bench: %s\n", t.name.c_str());
    results.push_back(run_gait_trial(t, o));
    for (const std::string& w : check_gait_result(results.back(), o)) print_warning("physics-bench", t.plates, w);
  }
  write_physics_report(results, c.out, c.force);
  std::printf("%-10s %-9s %9s %8s %9s %8s %9s %8s %8s\n", "trial", "source", "rmse_bw", "peak_%", "stance_ms",
              "lrate_%", "impulse_%", "flight", "cop_rms");
  for (const auto& r : results)
    for (const ForceSource* s : {&r.simulated, &r.naive})
      std::printf("%-10s %-9s %9s %8s %9s %8s %9s %8s %8s\n", r.trial.name.c_str(), s->name.c_str(),
                  figure(s->rmse_bw, 3).c_str(), figure(s->peak_error_pct, 1).c_str(),
                  figure(s->stance_error_ms, 0).c_str(), figure(s->loading_rate_error_pct, 0).c_str(),
                  figure(s->stride_impulse_error_pct, 1).c_str(), figure(s->flight_recall, 2).c_str(),
                  figure(s->cop_rms, 3).c_str());
  std::cout << "wrote " << c.out << "/index.html\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<PhysicsBenchCli>();
  auto* cmd = app.add_subcommand(
      "physics-bench",
      "Check the simulator against real force plates: each gait-lab trial (markers + plates) simulated\n"
      "on a body of the subject's sex, stature and mass; vertical force RMSE, peaks, stance, loading\n"
      "rate, stride impulse, flight and the centre of pressure along the foot, beside the naive\n"
      "reference (docs/physics.md).");
  cmd->add_option("--trials", c->trials, "Trials CSV (" + gait_trial_columns_text() + "; docs/physics.md)")->required();
  cmd->add_option("--data", c->data, "Folder the CSV's file names are relative to (default: the CSV's folder)");
  cmd->add_option("-o,--out", c->out, "Output folder (results.json, index.html, TRIAL_sim.mot)")->required();
  cmd->add_option("--fps", c->fps, "Simulation rate (default: each marker file's rate)")->check(in_range(0, 1000));
  cmd->add_flag("-f,--force", c->force, "Overwrite the output files");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(65, setup);
}  // namespace ptnet::cli::cmd_physics_bench
