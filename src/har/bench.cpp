// The body-shift HAR benchmark's run (ptnet/har_bench.hpp, docs/har_bench.md):
// populations simulated and read by the degraded mat, windows cut by the
// split, the deployment bodies' training windows synthesised per source,
// classifiers trained per source and scored on the deployment test windows
// (bench_score.cpp).
//
// Dimension legend: N windows, T frames, H x W mat cells, C classes,
// R recorded bodies, D deployment bodies.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "bench_internal.hpp"
#include "har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/strings.hpp"
#include "standin.hpp"

namespace ptnet::har {

void say(const BenchOptions& o, const std::string& line) {
  if (o.progress) o.progress(progress_line("har-bench", line));
}

bool is_transfer_source(const std::string& name) { return name == "model" || name == "model-mean"; }

bool is_baseline(const std::string& name) {
  return name != "recorded" && name != "oracle" && !is_transfer_source(name);
}

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

const std::vector<std::string>& known_syntheses() {
  static const std::vector<std::string> k = {"model",        "model-mean", "copy",
                                             "weight-ratio", "body-scale", "body-scale-read"};
  return k;
}

void check_options(const BenchOptions& o, const TransferFn& transfer) {
  if (o.runs < 1) throw Error("har-bench: runs must be at least 1, found " + std::to_string(o.runs));
  if (o.ensemble < 1)
    throw Error("har-bench: ensemble must be at least 1 classifier, found " + std::to_string(o.ensemble));
  if (o.stride < 1) throw Error("har-bench: stride must be at least 1, found " + std::to_string(o.stride));
  if (o.recorded_bodies < 1 || o.bodies_per_band < 1)
    throw Error("har-bench: need at least 1 recorded body and 1 body per deployment band");
  if (o.deployment_bands.empty()) throw Error("har-bench: no deployment band given");
  for (const auto& [list, what] : {std::pair{&o.deployment_bands, "deployment band"},
                                   std::pair{&o.syntheses, "training source"}, std::pair{&o.activities, "activity"}}) {
    std::vector<std::string> keys;
    for (const std::string& item : *list) keys.push_back(lower(item));
    if (const std::string twice = first_repeat(keys); !twice.empty())
      throw Error("har-bench: " + std::string(what) + " " + escaped(twice) + " given twice");
  }
  const std::vector<std::string> deployment = deployment_band_names();
  for (const std::string& b : o.deployment_bands) {
    body_band(b);
    if (std::find(deployment.begin(), deployment.end(), b) == deployment.end())
      throw Error("har-bench: band " + b + " is not a deployment band (mid is the recorded population, all the "
                  "transfer model's training bodies; deployment bands: " + join(deployment) + ")");
  }
  for (const std::string& s : o.syntheses) {
    if (std::find(known_syntheses().begin(), known_syntheses().end(), s) == known_syntheses().end())
      throw Error("har-bench: unknown training source '" + s + "' (sources: " + join(known_syntheses()) + ")");
    if (is_transfer_source(s) && !transfer)
      throw Error("har-bench: source '" + s + "' needs a transfer model");
  }
}

// Every clip on every body of a population, read by the degraded mat:
// [clip][body] sequences [T, H, W].
std::vector<std::vector<PressureSequence>> simulate_population(const BenchClips& clips,
                                                               const std::vector<BodySpec>& bodies,
                                                               const SimOptions& sim, const std::vector<float>& gain,
                                                               const BenchOptions& o) {
  std::vector<Body> b(bodies.begin(), bodies.end());
  const std::size_t nb = bodies.size();
  std::vector<Motion> copies(clips.clips.size() * nb);
  std::vector<MotionPlacement> placements(copies.size());
  std::vector<SimJob> jobs;
  for (std::size_t c = 0; c < clips.clips.size(); ++c) {
    const Motion& source = clips.clips[c].motion;
    const MotionPlacement place = place_motion(source, sim);
    for (std::size_t j = 0; j < nb; ++j) {
      const std::size_t k = c * nb + j;
      copies[k] = retarget(source, bodies[j].height_cm);
      placements[k] = place.scaled(retarget_scale(source, bodies[j].height_cm));
      const std::string name = clips.clips[c].source.meta.motion_id + "__" + bodies[j].id;
      jobs.push_back({&copies[k], &b[j], sequence_seed(o.seed, name), &placements[k], {}});
    }
  }
  std::vector<PressureSequence> seqs = simulate_many(jobs, sim, o.threads);
  std::vector<std::vector<PressureSequence>> out(clips.clips.size());
  for (std::size_t k = 0; k < seqs.size(); ++k) {
    degrade(seqs[k], gain, sim.sensor);
    out[k / nb].push_back(std::move(seqs[k]));
  }
  return out;
}

// Windows of frames [begin, end) of one sequence, every `stride` frames.
void add_windows(const PressureSequence& seq, int begin, int end, const BenchOptions& o, int label, int body,
                 const std::string& subject, bool features, Windows& w) {
  for (int t = begin; t + kWindowFrames <= end; t += o.stride) {
    const float* x = seq.frame(t);
    prepare_window(x, kWindowFrames, seq.mat, o.input, w.inputs);
    w.activity.push_back(label);
    w.body.push_back(body);
    if (features) {
      w.features.push_back(window_feature_vector(x, kWindowFrames, seq.mat, seq.fps));
      w.subject.push_back(subject);
    }
  }
}

// The first `frames` frames of a sequence.
PressureSequence head(const PressureSequence& s, int frames) {
  PressureSequence out(s.mat, frames, s.fps);
  std::copy(s.kpa.begin(), s.kpa.begin() + std::ptrdiff_t(out.kpa.size()), out.kpa.begin());
  return out;
}

// Pseudo labels of all real windows (recorded, oracle, test; the paper's
// features, per-subject normalisation, robust standardisation, PCA 4, mean
// shift). Returns the cluster count (< 2: no pseudo table).
int fit_pseudo_labels(std::vector<Windows*> sets, const BenchOptions& o, std::string& summary) {
  int n = 0;
  for (Windows* s : sets) n += s->count();
  const int nf = int(feature_names().size());
  Eigen::MatrixXd f(n, nf);
  std::vector<std::string> subject;
  int i = 0;
  for (Windows* s : sets)
    for (int k = 0; k < s->count(); ++k, ++i) {
      for (int j = 0; j < nf; ++j) f(i, j) = s->features[std::size_t(k)][std::size_t(j)];
      subject.push_back(s->subject[std::size_t(k)]);
    }
  normalise_per_subject(f, subject);
  robust_standardise(f);
  const Pca pca = Pca::fit(f, std::min(4, nf));
  const MeanShiftResult ms = mean_shift(pca.transform(f), {});
  i = 0;
  for (Windows* s : sets) {
    s->pseudo.assign(ms.labels.begin() + i, ms.labels.begin() + i + s->count());
    i += s->count();
  }
  summary = std::to_string(ms.clusters()) + " clusters, bandwidth " + fixed_text(ms.bandwidth) + ", silhouette " +
            fixed_text(ms.silhouette);
  return ms.clusters();
}

// The populations' simulations ([clip][body] sequences [T, H, W]) and the
// mat that read them.
struct Populations {
  SimOptions sim;
  std::vector<float> gain;  // [H x W] the mat's per-cell gains
  std::vector<std::vector<PressureSequence>> recorded, deployment;
};

// The real windows: recorded bodies' training parts; deployment bodies'
// training parts (the oracle) and test parts. first_window[c][j]: recorded
// body j's first window of clip c.
struct BenchWindows {
  Windows recorded, oracle, test;
  std::vector<std::vector<int>> first_window;
};

BenchWindows cut_windows(const BenchClips& clips, const Populations& p, const BenchResult& r, const BenchOptions& o) {
  const int R = int(r.recorded.size()), D = int(r.deployment.size());
  BenchWindows w;
  w.first_window.assign(clips.clips.size(), std::vector<int>(std::size_t(R), 0));
  for (std::size_t c = 0; c < clips.clips.size(); ++c) {
    const BenchClip& clip = clips.clips[c];
    for (int j = 0; j < R; ++j) {
      w.first_window[c][std::size_t(j)] = w.recorded.count();
      add_windows(p.recorded[c][std::size_t(j)], 0, clip.split.train_end, o, clip.label, -1,
                  r.recorded[std::size_t(j)].id, true, w.recorded);
    }
    for (int d = 0; d < D; ++d) {
      const PressureSequence& s = p.deployment[c][std::size_t(d)];
      const std::string& id = r.deployment[std::size_t(d)].id;
      add_windows(s, 0, clip.split.train_end, o, clip.label, d, id, true, w.oracle);
      add_windows(s, clip.split.test_begin, clip.split.frames, o, clip.label, d, id, true, w.test);
    }
  }
  return w;
}

// One training source's version of a recorded training part for body `to`.
PressureSequence synthesise(const std::string& name, const PressureSequence& part, const PressureSequence& transferred,
                            const BodySpec& from, const BodySpec& to, const std::string& motion_id,
                            const Populations& p, const BenchOptions& o) {
  const auto read = [&](PressureSequence s) {
    read_again(s, p.gain, p.sim.sensor, sequence_seed(o.seed, motion_id + "__" + to.id + "/read"));
    return s;
  };
  if (name == "model") return read(transferred);
  if (name == "model-mean") return transferred;
  if (name == "copy") return copy_baseline(part);
  if (name == "weight-ratio") return weight_ratio_baseline(part, from.weight_kg, to.weight_kg);
  PressureSequence s = body_scale_baseline(part, from, to);
  return name == "body-scale-read" ? read(std::move(s)) : s;
}

// The training sources: recorded, one per synthesis, oracle. A synthesis
// makes clip c's training part of recorded body (c + d) mod R into
// deployment body d's: as many windows as the oracle's.
std::vector<Synthesis> synthesise_sources(const BenchClips& clips, const Populations& p, const BenchWindows& real,
                                          const BenchResult& r, const BenchOptions& o, const TransferFn& transfer) {
  const int R = int(r.recorded.size()), D = int(r.deployment.size());
  std::vector<Synthesis> sources;
  sources.push_back({"recorded", {}});
  for (const std::string& name : o.syntheses) sources.push_back({name, {}});
  const bool transfers = std::any_of(o.syntheses.begin(), o.syntheses.end(), is_transfer_source);
  for (std::size_t c = 0; c < clips.clips.size(); ++c) {
    const BenchClip& clip = clips.clips[c];
    for (int d = 0; d < D; ++d) {
      const int j = int((c + std::size_t(d)) % std::size_t(R));
      const BodySpec &from = r.recorded[std::size_t(j)], &to = r.deployment[std::size_t(d)];
      const PressureSequence part = head(p.recorded[c][std::size_t(j)], clip.split.train_end);  // never the test part
      PressureSequence transferred;
      if (transfers) {
        transferred = transfer(part, from, to);
        if (!(transferred.mat == part.mat) || transferred.frames() != part.frames())
          throw Error("har-bench: the transfer of " + clip.source.meta.motion_id + " returned " +
                      std::to_string(transferred.frames()) + " frames, expected " + std::to_string(part.frames()));
      }
      for (std::size_t k = 1; k < sources.size(); ++k) {
        const PressureSequence s =
            synthesise(sources[k].name, part, transferred, from, to, clip.source.meta.motion_id, p, o);
        Windows& w = sources[k].extra;
        const int before = w.count();
        add_windows(s, 0, clip.split.train_end, o, clip.label, d, to.id, false, w);
        for (int i = 0; i < w.count() - before; ++i) w.source.push_back(real.first_window[c][std::size_t(j)] + i);
      }
    }
    if (transfers && ((c + 1) % 10 == 0 || c + 1 == clips.clips.size()))
      say(o, "har-bench: transferred " + std::to_string(c + 1) + "/" + std::to_string(clips.clips.size()) +
                 " clips onto " + std::to_string(D) + " deployment bodies");
  }
  sources.push_back({"oracle", real.oracle});
  return sources;
}

// The pseudo-label table (when mean shift finds 2+ clusters): synthesised
// windows take their source window's label.
void add_pseudo_table(std::vector<Synthesis>& sources, BenchWindows& real, BenchResult& r, const BenchOptions& o) {
  std::string summary;
  const int k = fit_pseudo_labels({&real.recorded, &sources.back().extra, &real.test}, o, summary);
  say(o, "har-bench: pseudo labels: " + summary);
  if (k < 2) {
    r.left_out.push_back("pseudo labels: mean shift found a single cluster");
    return;
  }
  for (std::size_t s = 1; s + 1 < sources.size(); ++s)
    for (int src : sources[s].extra.source) sources[s].extra.pseudo.push_back(real.recorded.pseudo[std::size_t(src)]);
  std::vector<std::string> names;
  for (int c = 0; c < k; ++c) names.push_back("cluster " + std::to_string(c));
  r.tables.push_back(score_table(sources, real.recorded, real.test, true, names, int(r.deployment.size()), o));
}

}  // namespace

BenchResult run_bench(const BenchOptions& o, const TransferFn& transfer) {
  const auto t0 = Clock::now();
  check_options(o, transfer);
  BenchResult r;
  r.mocap = o.mocap.empty() ? "procedural" : o.mocap;
  r.runs = o.runs;
  r.ensemble = o.ensemble;
  const BenchClips clips = load_bench_clips(o);
  if (!o.model_data.empty()) check_bench_training_set(o.model_data, clips);
  r.activities = clips.activities;
  r.left_out = clips.left_out;
  r.clips = int(clips.clips.size());
  r.recorded = band_bodies(body_band("mid"), o.recorded_bodies, o.seed, "rec", "original");
  for (const std::string& band : o.deployment_bands)
    for (BodySpec b : band_bodies(body_band(band), o.bodies_per_band, o.seed, band + "-", "original"))
      r.deployment.push_back(b);

  // 1. both populations, read by the degraded mat.
  Populations p{standin_sim_options(o.sensor), {}, {}, {}};
  p.gain = standin_gain_map(p.sim.mat, o.sensor);
  say(o, "har-bench: simulating " + std::to_string(r.clips) + " clips (" + join(r.activities) + ") on " +
             std::to_string(r.recorded.size()) + " recorded and " + std::to_string(r.deployment.size()) +
             " deployment bodies");
  p.recorded = simulate_population(clips, r.recorded, p.sim, p.gain, o);
  p.deployment = simulate_population(clips, r.deployment, p.sim, p.gain, o);
  r.simulate_seconds = since(t0);

  // 2. windows, 3. the training sources.
  BenchWindows real = cut_windows(clips, p, r, o);
  r.recorded_windows = real.recorded.count();
  r.test_windows = real.test.count();
  const auto t1 = Clock::now();
  std::vector<Synthesis> sources = synthesise_sources(clips, p, real, r, o, transfer);
  r.synthetic_windows = real.oracle.count();
  r.transfer_seconds = since(t1);

  // 4. classifiers per label kind and source.
  const auto t2 = Clock::now();
  say(o, "har-bench: " + std::to_string(r.recorded_windows) + " recorded training windows, " +
             std::to_string(r.synthetic_windows) + " per synthesis, " + std::to_string(r.test_windows) +
             " test windows; " + std::to_string(o.runs) + " runs per source of " + std::to_string(o.ensemble) +
             (o.ensemble > 1 ? " classifiers each" : " classifier each"));
  r.tables.push_back(
      score_table(sources, real.recorded, real.test, false, r.activities, int(r.deployment.size()), o));
  if (o.pseudo_labels) add_pseudo_table(sources, real, r, o);
  r.classify_seconds = since(t2);
  r.seconds = since(t0);
  return r;
}

}  // namespace ptnet::har
