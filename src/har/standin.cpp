// The stand-in for real pressure-mat recordings (ptnet/har.hpp, docs/har.md).
// Subjects on their own bodies (procedural performers, or the real clips of
// a mocap folder grouped by CMU subject), simulated with a degraded sensor
// profile. Clearly a stand-in: every file it writes says so.
//
// Dimension legend: T frames, H x W mat cells.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "ptnet/body.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "standin.hpp"

namespace ptnet::har {
namespace {

// Body-mass index of the stand-in subjects: Gaussian 23.5 +- 2.5 kg/m^2,
// clamped to 19-30 (a typical adult range).
constexpr double kBmiMean = 23.5, kBmiSd = 2.5, kBmiMin = 19, kBmiMax = 30;
// Stature of the mocap subjects (their rigs do not carry it: the CC clips
// share one 1.8 m dummy): the procedural performers' adult statures
// (src/motion/category.cpp), male 177 +- 7 cm, female 163 +- 6.5 cm.
constexpr double kMaleStatureCm = 177, kMaleStatureSdCm = 7;
constexpr double kFemaleStatureCm = 163, kFemaleStatureSdCm = 6.5;

// A subject's body: the given sex and height, weight from a seeded BMI
// (one distribution object per stand-in: it caches its second draw).
BodySpec subject_body(const std::string& id, Sex sex, double height_cm, std::mt19937_64& rng,
                      std::normal_distribution<double>& bmi) {
  BodySpec b;
  b.id = id;
  b.sex = sex;
  b.height_cm = std::round(std::clamp(height_cm, kMinHeightCm, kMaxHeightCm) * 10) / 10;
  const double h_m = b.height_cm / 100;
  b.weight_kg = std::round(std::clamp(bmi(rng), kBmiMin, kBmiMax) * h_m * h_m * 10) / 10;
  b.weight_kg = std::clamp(b.weight_kg, kMinWeightKg, kMaxWeightKg);
  b.role = "original";
  validate(b);
  return b;
}

// What the stand-in simulates: the subjects' bodies and, per clip, its
// motion (already on its subject's body), metadata and subject index.
struct StandinPlan {
  std::vector<BodySpec> bodies;
  std::vector<Motion> motions;
  std::vector<SequenceMeta> metas;
  std::vector<int> owner;  // [clips] index into bodies
  nlohmann::json config;
};

// Procedural performers first_performer.. on their own heights.
StandinPlan procedural_plan(const StandinOptions& o) {
  if (o.subjects < 2) throw Error("standin: need at least 2 subjects, found " + std::to_string(o.subjects));
  if (!(o.seconds >= 2)) throw Error("standin: clips must last at least 2 s");
  if (o.takes < 1) throw Error("standin: takes must be at least 1");
  StandinPlan p;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> bmi(kBmiMean, kBmiSd);
  for (int s = 0; s < o.subjects; ++s)
    p.bodies.push_back(subject_body("s" + std::to_string(s + 1), s % 2 == 0 ? Sex::female : Sex::male,
                                    std::round(performer_height_cm(o.first_performer + s, o.seed) * 10) / 10,
                                    rng, bmi));
  for (int s = 0; s < o.subjects; ++s)
    for (Category c : kCategories)
      for (int take = 1; take <= o.takes; ++take) {
        GenerateOptions g;
        g.category = c;
        g.performer = o.first_performer + s;
        g.take = take;
        g.seconds = o.seconds;
        g.height_cm = p.bodies[s].height_cm;
        g.seed = o.seed;
        p.motions.push_back(generate_motion(g));
        SequenceMeta m;
        m.motion_id = "standin_" + motion_id(g.performer, c, take);
        m.body_id = p.bodies[s].id;
        m.name = m.motion_id + "__" + m.body_id;
        m.performer = "P" + std::to_string(g.performer);
        m.category = category_name(c);
        m.take = take;
        m.source = "procedural:standin";
        p.metas.push_back(m);
        p.owner.push_back(s);
      }
  p.config = {{"subjects", o.subjects},
              {"first_performer", o.first_performer},
              {"seconds", o.seconds},
              {"takes", o.takes}};
  return p;
}

}  // namespace

namespace {

// Numeric subject ids sort numerically ("2" < "14" < "141"), others after.
bool subject_less(const std::string& a, const std::string& b) {
  const bool na = !a.empty() && std::all_of(a.begin(), a.end(), ::isdigit);
  const bool nb = !b.empty() && std::all_of(b.begin(), b.end(), ::isdigit);
  if (na && nb) return a.size() != b.size() ? a.size() < b.size() : a < b;
  if (na != nb) return na;
  return a < b;
}

// One subject per CMU subject of the folder's clips.csv, its clips
// retargeted onto its own sampled body.
StandinPlan mocap_plan(const StandinOptions& o) {
  const std::vector<ClipRow> clips = read_clips_csv((std::filesystem::path(o.mocap) / "clips.csv").string());
  std::vector<std::string> subjects;
  for (const auto& c : clips)
    if (std::find(subjects.begin(), subjects.end(), c.subject) == subjects.end()) subjects.push_back(c.subject);
  std::sort(subjects.begin(), subjects.end(), subject_less);
  if (subjects.size() < 2)
    throw Error::in(o.mocap + "/clips.csv", "need clips of at least 2 subjects, found " +
                                                std::to_string(subjects.size()));
  StandinPlan p;
  std::mt19937_64 rng(o.seed ^ 0x6d6f636170ULL);  // "mocap": its own stream
  std::normal_distribution<double> unit(0.0, 1.0), bmi(kBmiMean, kBmiSd);
  for (std::size_t s = 0; s < subjects.size(); ++s) {
    const Sex sex = s % 2 == 0 ? Sex::female : Sex::male;
    const double h = sex == Sex::male ? kMaleStatureCm + kMaleStatureSdCm * unit(rng)
                                      : kFemaleStatureCm + kFemaleStatureSdCm * unit(rng);
    p.bodies.push_back(subject_body("s" + subjects[s], sex, std::clamp(h, 150.0, 200.0), rng, bmi));
  }
  nlohmann::json listed = nlohmann::json::array();
  for (const auto& c : clips) {
    const int s = int(std::find(subjects.begin(), subjects.end(), c.subject) - subjects.begin());
    MotionOptions mo;
    mo.metres_per_unit = c.metres_per_unit;
    mo.up = c.up == "z" ? UpAxis::z : UpAxis::y;
    mo.fps = 30;
    p.motions.push_back(retarget(load_motion(c.file, mo), p.bodies[s].height_cm));
    SequenceMeta m;
    m.motion_id = "standin_" + std::filesystem::path(c.file).stem().string();
    m.body_id = p.bodies[s].id;
    m.name = m.motion_id + "__" + m.body_id;
    m.performer = "CMU" + c.subject;
    m.category = c.category;
    m.take = c.take;
    m.source = c.file;
    p.metas.push_back(m);
    p.owner.push_back(s);
    listed.push_back(std::filesystem::path(c.file).filename().string());
  }
  p.config = {{"mocap", o.mocap}, {"clips", listed}};
  return p;
}

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

SimOptions standin_sim_options(const StandinOptions& o) {
  SimOptions sim;
  sim.sensor.crosstalk = o.crosstalk;
  sim.sensor.noise_sd_kpa = o.noise_sd_kpa;
  sim.placement = parse_placement(o.placement);
  sim.seed = o.seed;
  return sim;
}

namespace {

// The sensor's activation threshold, saturation and ADC step on one reading.
float read_out(double v, const SensorModel& sm) {
  if (v < sm.threshold_kpa) v = 0;
  v = std::min(v, sm.saturation_kpa);
  if (sm.quantum_kpa > 0) v = std::round(v / sm.quantum_kpa) * sm.quantum_kpa;
  return float(v);
}

void check_gain(const PressureSequence& seq, const std::vector<float>& gain) {
  if (gain.size() != std::size_t(seq.mat.cells()))
    throw Error("standin: gain map of " + std::to_string(gain.size()) + " cells for a mat of " +
                std::to_string(seq.mat.cells()));
}

}  // namespace

void degrade(PressureSequence& seq, const std::vector<float>& gain, const SensorModel& sm) {
  check_gain(seq, gain);
  for (int t = 0; t < seq.frames(); ++t) {
    float* f = seq.frame(t);
    for (int i = 0; i < seq.mat.cells(); ++i) f[i] = read_out(double(f[i]) * gain[i], sm);
  }
}

void read_again(PressureSequence& seq, const std::vector<float>& gain, const SensorModel& sm,
                std::uint64_t seed) {
  check_gain(seq, gain);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sm.noise_sd_kpa);
  for (int t = 0; t < seq.frames(); ++t) {
    float* f = seq.frame(t);
    for (int i = 0; i < seq.mat.cells(); ++i) {
      const double n = sm.noise_sd_kpa > 0 ? noise(rng) : 0.0;
      f[i] = gain[i] == 0 ? 0.0f : read_out(double(f[i]) + n, sm);
    }
  }
}

// The one mechanism for both kinds of subjects: plan -> simulate -> degrade
// -> write.
void write_standin(const std::string& path, const StandinOptions& o, bool force) {
  check_dataset_output(path, force);
  auto say = [&](const std::string& s) {
    if (o.progress) o.progress(progress_line("standin", s));
  };
  StandinPlan plan = o.mocap.empty() ? procedural_plan(o) : mocap_plan(o);

  SimOptions sim = standin_sim_options(o);
  const std::vector<float> gain = standin_gain_map(sim.mat, o);
  std::vector<Body> bodies;
  for (const auto& b : plan.bodies) bodies.emplace_back(b);
  std::vector<SimJob> jobs;
  for (std::size_t i = 0; i < plan.motions.size(); ++i)
    jobs.push_back(
        {&plan.motions[i], &bodies[plan.owner[i]], sequence_seed(o.seed, plan.metas[i].name), nullptr, {}});
  say("standin: simulating " + std::to_string(jobs.size()) + " clips of " +
      std::to_string(plan.bodies.size()) + " subjects" + (o.mocap.empty() ? "" : " (mocap " + o.mocap + ")"));
  std::vector<PressureSequence> seqs = simulate_many(jobs, sim, o.threads);
  for (PressureSequence& seq : seqs) degrade(seq, gain, sim.sensor);

  DatasetInfo info;
  info.mat = sim.mat;
  info.fps = plan.motions.empty() ? 30 : plan.motions[0].fps;
  info.generator = std::string("ptnet ") + PTNET_VERSION + " standin";
  nlohmann::json cfg = plan.config;
  cfg["kind"] = "stand-in for real recordings (simulated, not real data)";
  cfg["crosstalk"] = o.crosstalk;
  cfg["noise_sd_kpa"] = o.noise_sd_kpa;
  cfg["gain_sd"] = o.gain_sd;
  cfg["dead_fraction"] = o.dead_fraction;
  cfg["placement"] = placement_name(sim.placement);
  cfg["seed"] = o.seed;
  info.config_json = cfg.dump();
  DatasetWriter w(path, info, plan.bodies, force);
  for (std::size_t i = 0; i < seqs.size(); ++i) w.add(plan.metas[i], seqs[i]);
  w.commit();
  say("standin: wrote " + path);
}

}  // namespace ptnet::har
