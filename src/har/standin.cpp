// The stand-in for real pressure-mat recordings (ptnet/har.hpp, docs/har.md).
// Procedural performers on their own bodies, simulated with a degraded
// sensor profile. Clearly a stand-in: every file it writes says so.
//
// Dimension legend: T frames, H x W mat cells.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "ptnet/body.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"

namespace ptnet::har {
namespace {

// Body-mass index of the stand-in subjects: Gaussian 23.5 +- 2.5 kg/m^2,
// clamped to 19-30 (a typical adult range).
constexpr double kBmiMean = 23.5, kBmiSd = 2.5, kBmiMin = 19, kBmiMax = 30;

}  // namespace

// [H, W] gains: exp(N(0, gain_sd)) per cell, dead cells 0.
std::vector<float> standin_gain_map(const MatSpec& mat, const StandinOptions& o) {
  std::mt19937_64 rng(o.seed ^ 0x5eed5a17d1ULL);
  std::normal_distribution<double> g(0.0, o.gain_sd);
  std::vector<float> gain(mat.cells());
  for (float& v : gain) v = float(std::exp(g(rng)));
  const int dead = int(std::lround(o.dead_fraction * mat.cells()));
  std::vector<int> idx(mat.cells());
  for (int i = 0; i < mat.cells(); ++i) idx[i] = i;
  for (int i = 0; i < dead; ++i) {  // partial Fisher-Yates: `dead` distinct cells
    std::uniform_int_distribution<int> pick(i, mat.cells() - 1);
    std::swap(idx[i], idx[pick(rng)]);
    gain[idx[i]] = 0.0f;
  }
  return gain;
}

void write_standin(const std::string& path, const StandinOptions& o, bool force) {
  if (o.subjects < 2) throw Error("standin: need at least 2 subjects, found " + std::to_string(o.subjects));
  if (!(o.seconds >= 2)) throw Error("standin: clips must last at least 2 s");
  if (o.takes < 1) throw Error("standin: takes must be at least 1");
  auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  SimOptions sim;
  sim.sensor.crosstalk = o.crosstalk;
  sim.sensor.noise_sd_kpa = o.noise_sd_kpa;
  sim.seed = o.seed;
  const std::vector<float> gain = standin_gain_map(sim.mat, o);

  // Subjects: s1..sN, sex alternating, the performer's own height.
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> bmi(kBmiMean, kBmiSd);
  std::vector<BodySpec> specs;
  for (int s = 0; s < o.subjects; ++s) {
    BodySpec b;
    b.id = "s" + std::to_string(s + 1);
    b.sex = s % 2 == 0 ? Sex::female : Sex::male;
    b.height_cm = std::round(performer_height_cm(o.first_performer + s, o.seed) * 10) / 10;
    const double h_m = b.height_cm / 100;
    b.weight_kg = std::round(std::clamp(bmi(rng), kBmiMin, kBmiMax) * h_m * h_m * 10) / 10;
    b.weight_kg = std::clamp(b.weight_kg, kMinWeightKg, kMaxWeightKg);
    b.role = "original";
    validate(b);
    specs.push_back(b);
  }
  std::vector<Body> bodies;
  for (const auto& b : specs) bodies.emplace_back(b);

  std::vector<Motion> motions;
  std::vector<SequenceMeta> metas;
  std::vector<int> owner;
  for (int s = 0; s < o.subjects; ++s)
    for (Category c : kCategories)
      for (int take = 1; take <= o.takes; ++take) {
        GenerateOptions g;
        g.category = c;
        g.performer = o.first_performer + s;
        g.take = take;
        g.seconds = o.seconds;
        g.height_cm = specs[s].height_cm;
        g.seed = o.seed;
        motions.push_back(generate_motion(g));
        SequenceMeta m;
        m.motion_id = "standin_p" + std::to_string(g.performer) + "_" + category_name(c) + "_t" +
                      std::to_string(take);
        m.body_id = specs[s].id;
        m.name = m.motion_id + "__" + m.body_id;
        m.performer = "P" + std::to_string(g.performer);
        m.category = category_name(c);
        m.take = take;
        m.source = "procedural:standin";
        metas.push_back(m);
        owner.push_back(s);
      }
  std::vector<SimJob> jobs;
  for (std::size_t i = 0; i < motions.size(); ++i)
    jobs.push_back({&motions[i], &bodies[owner[i]], sequence_seed(o.seed, metas[i].name)});
  say("standin: simulating " + std::to_string(jobs.size()) + " clips of " +
      std::to_string(o.subjects) + " subjects");
  std::vector<PressureSequence> seqs = simulate_many(jobs, sim, o.threads);

  // The degraded sensor: per-cell gain, dead cells, then the activation
  // threshold, saturation and ADC step of the simulator's sensor again.
  const SensorModel& sm = sim.sensor;
  for (PressureSequence& seq : seqs)
    for (int t = 0; t < seq.frames(); ++t) {
      float* f = seq.frame(t);
      for (int i = 0; i < seq.mat.cells(); ++i) {
        double v = double(f[i]) * gain[i];
        if (v < sm.threshold_kpa) v = 0;
        v = std::min(v, sm.saturation_kpa);
        if (sm.quantum_kpa > 0) v = std::round(v / sm.quantum_kpa) * sm.quantum_kpa;
        f[i] = float(v);
      }
    }

  DatasetInfo info;
  info.mat = sim.mat;
  info.fps = motions.empty() ? 30 : motions[0].fps;
  info.generator = std::string("ptnet ") + PTNET_VERSION + " standin";
  nlohmann::json cfg = {{"kind", "stand-in for real recordings (simulated, not real data)"},
                        {"subjects", o.subjects},
                        {"first_performer", o.first_performer},
                        {"seconds", o.seconds},
                        {"takes", o.takes},
                        {"crosstalk", o.crosstalk},
                        {"noise_sd_kpa", o.noise_sd_kpa},
                        {"gain_sd", o.gain_sd},
                        {"dead_fraction", o.dead_fraction},
                        {"seed", o.seed}};
  info.config_json = cfg.dump();
  DatasetWriter w(path, info, specs, force);
  for (std::size_t i = 0; i < seqs.size(); ++i) w.add(metas[i], seqs[i]);
  w.commit();
  say("standin: wrote " + path);
}

}  // namespace ptnet::har
