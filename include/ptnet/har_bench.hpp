// ptnet/har_bench.hpp: the body-shift HAR benchmark (docs/har_bench.md). Does
// transferred pressure help an activity classifier recognise people of
// bodies it never saw?
//
//   // 1. the transfer model's training set: the clips' training parts only
//   ptnet::har::BenchOptions o;
//   o.mocap = "corpus";                  // or empty: procedural clips
//   ptnet::har::write_bench_training_set("hb_train.h5", o, /*bodies=*/24, /*force=*/false);
//   //    ... ptnet train --data hb_train.h5 --out hb_model --preset fast
//   // 2. the benchmark
//   ptnet::har::BenchResult r = ptnet::har::run_bench(o, transfer_fn);   // TransferFn: har.hpp
//   std::cout << ptnet::har::format_bench(r);
//   ptnet::har::write_bench_report("out", r, /*force=*/false);      // index.html, f1.svg
//
// The design: every clip is performed by a *recorded* population (bodies
// of band "mid") and a *deployment* population (bands outside it), all read
// by one degraded sensor (the stand-in's, StandinOptions). Each clip's
// frames are cut in time into a training part and a test part
// with a gap of one window. A classifier learns from the recorded bodies'
// training parts plus, per source, the same number of windows for the
// deployment bodies (transfer, copy, weight ratio, body scale, or the
// oracle: the deployment bodies simulated directly), and is scored on the
// deployment bodies' test parts. Test parts are never transferred and never
// reach the transfer model's training (its training set holds only
// training parts, write_bench_training_set, and run_bench checks that).
//
// Dimension legend: N windows, T = 30 frames per window, H x W = 80 x 28
// mat cells, C activities (or pseudo-label clusters). Pressure in kPa.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {

// The bands a deployment population may come from (docs/har_bench.md,
// "Bands"): every band but mid (the recorded population) and all (the
// transfer model's training bodies).
std::vector<std::string> deployment_band_names();

inline StandinOptions follow_sensor() {
  StandinOptions s;
  s.placement = "follow";
  return s;
}

// The benchmark's classifier: class-balanced loss (activities are far from
// equally common: 17 of the corpus's 44 clips are dance), a cosine
// learning-rate schedule (a steadier last epoch: a smaller spread over runs)
// and 4 epochs (4, 6 and 10 scored within 0.005 on the corpus: the time
// goes to an ensemble per run instead, BenchOptions::ensemble).
inline ClassifierOptions bench_classifier() {
  ClassifierOptions c;
  c.balanced = true;
  c.cosine = true;
  c.epochs = 4;
  return c;
}

struct BenchOptions {
  std::string mocap;                  // folder with clips.csv (activity column) + BVH; empty: procedural
  std::vector<std::string> activities;  // empty: every activity with a usable clip (others left out)
  int recorded_bodies = 6;            // of band "mid"
  // The first pair of the sweep (docs/har_bench.md) whose oracle - recorded
  // gap reached 0.05 macro F1 on the corpus.
  std::vector<std::string> deployment_bands{"xsmall", "xlarge"};
  // Deployment bodies per band: at 4 the model's margin over body scale on
  // the corpus is 2.1 paired sd against 1.4 at 2 (docs/results.md, Table 3).
  int bodies_per_band = 4;
  // Training sources besides "recorded" (always first) and "oracle" (always
  // last): model (transfer, then read by the deployment mat: noise, dead
  // cells, threshold, ADC), model-mean (the transfer alone), copy,
  // weight-ratio, body-scale, body-scale-read (body scale, then read by
  // the deployment mat like model).
  std::vector<std::string> syntheses{"model", "copy", "weight-ratio", "body-scale-read"};
  int runs = 10;                      // seeded runs per source and label kind
  // Classifiers per run, their class probabilities averaged (member k of run
  // r has seed classifier.seed + r x ensemble + k): a run's F1 varies less
  // with the seeds (on the corpus sd ~0.02 at 3 and 5 against ~0.023 for one).
  int ensemble = 3;
  int stride = 5;                     // frames between window starts
  bool pseudo_labels = false;         // a second table: mean-shift pseudo labels
  InputOptions input{6, 2};           // 2: 4 cm cells (foot shape survives pooling)
  ClassifierOptions classifier = bench_classifier();  // seeds: see ensemble
  // Classifiers trained at once, each on one LibTorch thread (0: one per
  // core; 1: one at a time on classifier.threads). The result depends on
  // the LibTorch threads per classifier only: workers > 1 gives the same
  // as workers 1 with classifier.threads 1.
  int workers = 0;
  // The degraded sensor (crosstalk, noise, per-cell gain, dead cells) and
  // the placement (follow: real clips leave a fixed mat).
  StandinOptions sensor = follow_sensor();
  // Procedural clips (mocap empty): performers x 4 categories (the activity),
  // `seconds` long.
  int performers = 3;
  double seconds = 12;
  std::uint64_t seed = 1;             // bodies, sensor noise, procedural motions
  int threads = 0;                    // simulation threads (0: all cores)
  // The transfer model's training set (write_bench_training_set's output):
  // checked to hold only training parts of these clips; empty: not checked.
  std::string model_data;
  ProgressFn progress;                // a line {"har-bench", line} per step
};

// The transfer model's training set for the benchmark: every usable clip's
// training part (motion frames [0, train_end), so no test frame reaches the
// model) simulated on `bodies` bodies of band "all" (role retargeted, take
// 1) with the training sensor (SimOptions defaults) and the benchmark's
// placement; the config records the split ("har_bench_split"). Written
// atomically; refuses to overwrite without force.
void write_bench_training_set(const std::string& path, const BenchOptions& options, int bodies, bool force);

// One training source's classifiers for one label kind.
struct BenchSource {
  std::string name;                   // recorded, model, ..., oracle
  int train_windows = 0;
  std::vector<double> macro_f1;       // [runs]
  double mean = 0, sd = 0;            // of macro_f1 (sample sd)
  double gap_closed = 0;              // (mean - recorded) / (oracle - recorded); NaN for recorded/oracle
  std::vector<double> class_f1;       // [C] mean over runs
  std::vector<std::vector<double>> body_f1;  // [deployment body][runs] macro F1 on that body's windows
  std::vector<std::vector<double>> band_f1;  // [deployment band][runs] macro F1 on that band's windows
  Eigen::MatrixXi confusion;          // [C, C] summed over runs
};

// A transfer source (model, model-mean) against a baseline (copy,
// weight-ratio, body-scale, body-scale-read), run by run: run r of every
// source trains from the same seeds, so runs pair up.
struct BenchComparison {
  std::string source, baseline;
  std::string band;                   // a deployment band's windows only; empty: every deployment body's
  double difference = 0;              // mean over runs of source - baseline macro F1
  double paired_sd = 0;               // sample sd over runs of that difference
  double run_sd = 0;                  // the larger of the two sources' sd over runs
  int wins = 0;                       // runs in which the source scores higher
};

struct BenchTable {
  std::string labels;                 // "activity" or "pseudo"
  std::vector<std::string> classes;   // [C]
  std::vector<int> test_support;      // [C] test windows per class
  std::vector<BenchSource> sources;   // recorded, syntheses..., oracle
  double gap = 0;                     // oracle - recorded mean macro F1
  std::vector<std::string> bands;     // deployment bands scored apart (when there are 2+)
  // Every transfer source x every baseline present: on every deployment
  // body's test windows, then on each band's.
  std::vector<BenchComparison> comparisons;
};

struct BenchResult {
  std::string mocap;                  // or "procedural"
  std::vector<std::string> activities;
  std::vector<std::string> left_out;  // "clip: reason" / "activity: reason"
  std::vector<BodySpec> recorded, deployment;
  int clips = 0, recorded_windows = 0, synthetic_windows = 0, test_windows = 0;
  int runs = 0, ensemble = 1;       // runs per source, classifiers per run
  std::vector<BenchTable> tables;     // activity, then pseudo (when run)
  double simulate_seconds = 0, transfer_seconds = 0, classify_seconds = 0, seconds = 0;
};

// The benchmark (docs/har_bench.md): simulate the populations, cut the
// clips, synthesise the deployment bodies' training windows per source
// (`transfer` for model and model-mean; may be empty when neither is
// asked), train options.runs ensembles of options.ensemble classifiers
// per source and label kind, score them on the deployment bodies' test windows. Throws Error for unknown
// bands, sources or activities, an activity without a usable clip (when
// activities were named), fewer than 2 activities, or a model_data that is
// not a training set of these clips.
BenchResult run_bench(const BenchOptions& options, const TransferFn& transfer);

std::string format_bench(const BenchResult& result);  // the tables as text
std::string bench_json(const BenchResult& result);    // results.json (pretty)
// index.html (tables, per-activity F1, per-body F1, confusions, bodies) and
// f1.svg (macro F1 per source, whiskers +- 1 sd) into out_dir; returns the
// paths written.
std::vector<std::string> write_bench_report(const std::string& out_dir, const BenchResult& result, bool force);

}  // namespace ptnet::har
