// The body-shift HAR benchmark (ptnet/har_bench.hpp): bands, the split in
// time, the degraded mat, the transfer model's training set, and the whole
// benchmark on procedural clips (no ../shared needed).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include "har/bench_internal.hpp"
#include "har/standin.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har_bench.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace fs = std::filesystem;
using namespace ptnet;
using namespace ptnet::har;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("ptnet_har_bench_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(p);
  return p;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Small procedural benchmark options: 2 performers x 4 activities of 8 s.
BenchOptions small_options() {
  BenchOptions o;
  o.performers = 2;
  o.seconds = 8;
  o.recorded_bodies = 2;
  o.bodies_per_band = 1;
  o.runs = 2;
  o.ensemble = 1;
  o.classifier.epochs = 2;
  o.pseudo_labels = true;
  o.threads = 2;
  o.workers = 2;
  o.syntheses = {"copy", "body-scale"};
  return o;
}

}  // namespace

TEST(HarBenchSplit, TrainingAndTestPartsAreSeparatedByOneWindow) {
  for (int frames : {90, 91, 120, 200, 731, 5000}) {
    const ClipSplit s = split_clip(frames);
    ASSERT_TRUE(s.usable()) << frames;
    EXPECT_EQ(s.test_begin - s.train_end, kWindowFrames) << frames;  // the gap
    EXPECT_GE(s.train_end, kWindowFrames);
    EXPECT_GE(s.frames - s.test_begin, kWindowFrames);
    EXPECT_EQ(s.frames - s.test_begin, std::max(kWindowFrames, int(std::floor(kTestFraction * (frames - 30)))));
  }
  EXPECT_FALSE(split_clip(89).usable());  // fewer than 3 windows
  EXPECT_FALSE(split_clip(0).usable());
  EXPECT_EQ(split_clip(90).train_end, 30);
}

TEST(HarBenchBands, BodiesLieInTheirBandAndCoverIt) {
  for (const BodyBand& band : body_bands()) {
    const std::vector<BodySpec> b = band_bodies(band, 8, 3, "x", "original");
    ASSERT_EQ(b.size(), 8u);
    std::set<int> height_strata, bmi_strata;
    int female = 0;
    for (const BodySpec& x : b) {
      const double bmi = x.weight_kg / (x.height_cm * x.height_cm / 1e4);
      EXPECT_GE(x.height_cm, band.height_min_cm) << band.name;
      EXPECT_LE(x.height_cm, band.height_max_cm) << band.name;
      EXPECT_GE(bmi, band.bmi_min - 0.05) << band.name;
      EXPECT_LE(bmi, band.bmi_max + 0.05) << band.name;
      height_strata.insert(int((x.height_cm - band.height_min_cm) / (band.height_max_cm - band.height_min_cm) * 8));
      bmi_strata.insert(int((bmi - band.bmi_min) / (band.bmi_max - band.bmi_min) * 8));
      female += x.sex == Sex::female;
    }
    EXPECT_EQ(height_strata.size(), 8u) << band.name << ": every stature stratum once";
    EXPECT_EQ(bmi_strata.size(), 8u) << band.name << ": every BMI stratum once";
    EXPECT_EQ(female, 4);
  }
  // Deterministic in the seed, different with another.
  EXPECT_EQ(band_bodies(body_band("small"), 4, 1, "s", "original")[2].weight_kg,
            band_bodies(body_band("small"), 4, 1, "s", "original")[2].weight_kg);
  const std::string e = error_of([] { body_band("giant"); });
  EXPECT_NE(e.find("unknown body band 'giant'"), std::string::npos) << e;
  EXPECT_NE(e.find("small"), std::string::npos) << e;
}

TEST(HarBenchBands, DeploymentBandsLieOutsideTheRecordedOne) {
  const BodyBand& mid = body_band("mid");
  for (const std::string& name : deployment_band_names()) {
    const BodyBand& b = body_band(name);
    const bool outside_height = b.height_max_cm < mid.height_min_cm || b.height_min_cm > mid.height_max_cm;
    const bool outside_bmi = b.bmi_max < mid.bmi_min || b.bmi_min > mid.bmi_max;
    EXPECT_TRUE(outside_height || outside_bmi) << b.name;
  }
  EXPECT_EQ(deployment_band_names().size(), body_bands().size() - 2);
  const BodyBand& all = body_band("all");
  for (const BodyBand& b : body_bands()) {
    EXPECT_LE(all.height_min_cm, b.height_min_cm) << b.name;
    EXPECT_GE(all.height_max_cm, b.height_max_cm) << b.name;
    EXPECT_LE(all.bmi_min, b.bmi_min) << b.name;
    EXPECT_GE(all.bmi_max, b.bmi_max) << b.name;
  }
}

TEST(HarBenchSensor, TheMatReadsATransferLikeASimulation) {
  PressureSequence s(MatSpec{}, 2, 30);
  for (float& v : s.kpa) v = 50;
  s.kpa[5] = 0.5f;  // below the threshold
  StandinOptions so;
  std::vector<float> gain = standin_gain_map(s.mat, so);
  gain[7] = 0;  // a dead cell
  SensorModel sm = standin_sim_options(so).sensor;
  PressureSequence a = s, b = s, c = s;
  read_again(a, gain, sm, 1);
  read_again(b, gain, sm, 1);
  read_again(c, gain, sm, 2);
  EXPECT_EQ(a.kpa, b.kpa) << "same seed, same reading";
  EXPECT_NE(a.kpa, c.kpa) << "another seed, other noise";
  EXPECT_EQ(a.kpa[7], 0.0f);
  EXPECT_EQ(a.kpa[5], 0.0f);
  double mean = 0, var = 0;
  int live = 0;
  for (std::size_t i = 100; i < a.kpa.size(); ++i)
    if (gain[i % gain.size()] > 0) {
      mean += a.kpa[i];
      ++live;
    }
  mean /= live;
  for (std::size_t i = 100; i < a.kpa.size(); ++i)
    if (gain[i % gain.size()] > 0) var += (a.kpa[i] - mean) * (a.kpa[i] - mean) / live;
  EXPECT_NEAR(mean, 50, 0.1) << "no gain applied: the reading is unbiased";
  EXPECT_NEAR(std::sqrt(var), sm.noise_sd_kpa, 0.1 * sm.noise_sd_kpa + 0.05) << "the mat's noise";
  degrade(b = s, gain, sm);
  EXPECT_EQ(b.kpa[7], 0.0f);
  EXPECT_NEAR(b.kpa[9], std::round(50 * gain[9] * 10) / 10, 1e-4) << "degrade applies the cell's gain";
}

TEST(HarBenchClips, ClipsTooShortToSplitAreLeftOutOrRefused) {
  BenchOptions o = small_options();
  o.seconds = 2;  // 60 frames: no clip holds 3 windows
  std::string e = error_of([&] { run_bench(o, {}); });
  EXPECT_NE(e.find("need clips of at least 2 activities with a test window, found 0"), std::string::npos) << e;
  o.activities = {"walking"};
  e = error_of([&] { run_bench(o, {}); });
  EXPECT_NE(e.find("activity 'walking' has no test window"), std::string::npos) << e;
  EXPECT_NE(e.find("leave the activity out"), std::string::npos) << e;
  o = small_options();
  o.activities = {"swimming"};
  e = error_of([&] { run_bench(o, {}); });
  EXPECT_NE(e.find("no clip of activity 'swimming'"), std::string::npos) << e;
}

TEST(HarBenchOptions, BadSourcesAndBandsAreRefusedBeforeAnyWork) {
  BenchOptions o = small_options();
  o.syntheses = {"copy", "magic"};
  EXPECT_NE(error_of([&] { run_bench(o, {}); }).find("unknown training source 'magic'"), std::string::npos);
  o.syntheses = {"model"};
  EXPECT_NE(error_of([&] { run_bench(o, {}); }).find("needs a transfer model"), std::string::npos);
  o = small_options();
  o.deployment_bands = {"mid"};
  EXPECT_NE(error_of([&] { run_bench(o, {}); }).find("band mid is not a deployment band"), std::string::npos);
  o.deployment_bands = {"xsmall", "all"};  // all covers mid: not outside the recorded population
  EXPECT_NE(error_of([&] { run_bench(o, {}); }).find("band all is not a deployment band"), std::string::npos);
  // A list item twice would be scored twice (before: xsmall,xlarge,xsmall ran xsmall twice).
  o.deployment_bands = {"xsmall", "xlarge", "xsmall"};
  EXPECT_EQ(error_of([&] { run_bench(o, {}); }), "har-bench: deployment band 'xsmall' given twice");
  o = small_options();
  o.syntheses = {"copy", "body-scale", "Copy"};
  EXPECT_EQ(error_of([&] { run_bench(o, {}); }), "har-bench: training source 'copy' given twice");
}

TEST(HarBenchTrainingSet, HoldsOnlyTrainingPartsAndIsCheckedForIt) {
  const fs::path dir = scratch("training_set");
  fs::create_directories(dir);
  BenchOptions o = small_options();
  const std::string path = (dir / "train.h5").string();
  write_bench_training_set(path, o, 4, false);
  const Dataset d = Dataset::open(path);
  EXPECT_EQ(d.bodies().size(), 4u);
  const int part = split_clip(int(std::lround(o.seconds * kFps)) + 1).train_end;
  ASSERT_FALSE(d.sequences().empty());
  for (const SequenceMeta& s : d.sequences()) {
    EXPECT_LE(s.frames, part) << s.name << ": only the training part";
    EXPECT_EQ(s.take, 1);
  }
  for (const BodySpec& b : d.bodies()) EXPECT_EQ(b.role, "retargeted");
  EXPECT_NO_THROW(check_bench_training_set(path, o));
  EXPECT_THROW(write_bench_training_set(path, o, 4, false), Error) << "no overwrite without force";

  // Whole clips (a plain simulate) are refused: their test parts reached the model.
  const std::string whole = (dir / "whole.h5").string();
  SimulateDatasetOptions so;
  so.threads = 2;
  simulate_dataset(embedded_clips(o.performers, 1, o.seconds, o.seed), {BodySpec{"b", Sex::male, 180, 80, "retargeted"}},
                   whole, so);
  const std::string e = error_of([&] { check_bench_training_set(whole, o); });
  EXPECT_NE(e.find("expected a har-bench training set"), std::string::npos) << e;
  fs::remove_all(dir);
}

TEST(HarBench, ProceduralBenchmarkScoresEverySourceOnTheDeploymentBodies) {
  BenchOptions o = small_options();
  o.deployment_bands = {"short", "tall"};
  const BenchResult r = run_bench(o, {});
  ASSERT_EQ(r.activities, (std::vector<std::string>{"acting", "freestyle", "rom", "walking"}));
  ASSERT_EQ(r.recorded.size(), 2u);
  ASSERT_EQ(r.deployment.size(), 2u);
  EXPECT_LT(r.deployment[0].height_cm, 160);
  EXPECT_GT(r.deployment[1].height_cm, 178);
  ASSERT_GE(r.tables.size(), 1u);
  const BenchTable& t = r.tables[0];
  EXPECT_EQ(t.labels, "activity");
  ASSERT_EQ(t.sources.size(), 4u);
  EXPECT_EQ(t.sources.front().name, "recorded");
  EXPECT_EQ(t.sources.back().name, "oracle");
  // Equal window counts for every added source: the deployment bodies' training parts.
  for (std::size_t i = 1; i < t.sources.size(); ++i)
    EXPECT_EQ(t.sources[i].train_windows, r.recorded_windows + r.synthetic_windows) << t.sources[i].name;
  EXPECT_EQ(t.sources[0].train_windows, r.recorded_windows);
  // One recorded body's training part per clip and deployment body.
  EXPECT_EQ(r.synthetic_windows * int(r.recorded.size()), r.recorded_windows * int(r.deployment.size()));
  int support = 0;
  for (int n : t.test_support) {
    EXPECT_GT(n, 0) << "every activity has test windows";
    support += n;
  }
  EXPECT_EQ(support, r.test_windows);
  for (const BenchSource& s : t.sources) {
    ASSERT_EQ(s.macro_f1.size(), 2u);
    for (double f : s.macro_f1) {
      EXPECT_GT(f, 1.0 / 4) << s.name << ": better than chance on 4 activities";
      EXPECT_LE(f, 1.0);
    }
    EXPECT_EQ(s.confusion.sum(), 2 * r.test_windows) << "every test window scored in every run";
    ASSERT_EQ(s.body_f1.size(), 2u);
    // One body per band: a band's windows are its body's.
    EXPECT_EQ(s.band_f1, s.body_f1) << s.name;
  }
  EXPECT_TRUE(std::isnan(t.sources.front().gap_closed));
  EXPECT_NEAR(t.gap, t.sources.back().mean - t.sources.front().mean, 1e-12);
  // Same seed, same result, whether the classifiers train one at a time or at once.
  o.workers = 1;
  o.classifier.threads = 1;
  const BenchResult again = run_bench(o, {});
  for (std::size_t s = 0; s < t.sources.size(); ++s)
    EXPECT_EQ(again.tables[0].sources[s].macro_f1, t.sources[s].macro_f1) << t.sources[s].name;
  // The outputs.
  const fs::path dir = scratch("report");
  fs::create_directories(dir);
  const auto written = write_bench_report(dir.string(), r, false);
  EXPECT_EQ(written.size(), 2u);
  for (const auto& p : written) EXPECT_GT(fs::file_size(p), 500u) << p;
  const std::string json = bench_json(r);
  EXPECT_NE(json.find("\"gap_closed\""), std::string::npos);
  EXPECT_NE(format_bench(r).find("oracle"), std::string::npos);
  fs::remove_all(dir);
}

TEST(HarBench, TheTransferFunctionSeesOnlyTrainingParts) {
  BenchOptions o = small_options();
  o.runs = 1;
  o.ensemble = 1;
  o.classifier.epochs = 1;
  o.syntheses = {"model", "model-mean"};
  int calls = 0;
  const auto transfer = [&](const PressureSequence& s, const BodySpec& from, const BodySpec& to) {
    ++calls;
    const int whole = int(std::lround(o.seconds * kFps));
    EXPECT_GE(s.frames(), kWindowFrames);
    EXPECT_LE(s.frames(), split_clip(whole + 1).train_end) << "only the training part";
    EXPECT_EQ(from.id.rfind("rec", 0), 0u);
    EXPECT_EQ(to.id.rfind("rec", 0), std::string::npos);
    return s;
  };
  const BenchResult r = run_bench(o, transfer);
  EXPECT_EQ(calls, r.clips * int(r.deployment.size())) << "one transfer per clip and deployment body";
  ASSERT_EQ(r.tables[0].sources.size(), 4u);
  EXPECT_EQ(r.tables[0].sources[1].name, "model");
  EXPECT_EQ(r.tables[0].sources[2].name, "model-mean");
}

TEST(HarBench, RunsOfEverySourceTrainFromTheSameSeeds) {
  BenchOptions o = small_options();
  o.ensemble = 2;
  o.classifier.epochs = 1;
  o.pseudo_labels = false;
  o.syntheses = {"model-mean", "copy"};
  // An identity transfer makes model-mean's windows copy's windows.
  const auto identity = [](const PressureSequence& s, const BodySpec&, const BodySpec&) { return s; };
  const BenchResult r = run_bench(o, identity);
  EXPECT_EQ(r.ensemble, 2);
  const BenchTable& t = r.tables[0];
  ASSERT_EQ(t.sources.size(), 4u);
  ASSERT_EQ(t.sources[1].macro_f1.size(), 2u);
  EXPECT_EQ(t.sources[1].macro_f1, t.sources[2].macro_f1) << "the same windows and seeds, the same scores";
  // The whole population, then each of its two bands (xsmall, xlarge): the
  // transfer against the baseline and against the oracle, the oracle
  // against the baseline (the headroom).
  ASSERT_EQ(t.comparisons.size(), 9u);
  EXPECT_EQ(t.bands, o.deployment_bands);
  const BenchSource& copy = t.sources[2];
  const BenchSource& oracle = t.sources[3];
  ASSERT_EQ(oracle.name, "oracle");
  const std::pair<std::string, std::string> expected[] = {
      {"model-mean", "copy"}, {"model-mean", "oracle"}, {"oracle", "copy"}};
  for (std::size_t i = 0; i < t.comparisons.size(); ++i) {
    const BenchComparison& c = t.comparisons[i];
    const int band = int(i / 3) - 1;
    EXPECT_EQ(c.band, band < 0 ? "" : o.deployment_bands[std::size_t(band)]);
    EXPECT_EQ(std::make_pair(c.source, c.baseline), expected[i % 3]) << i;
    if (c.baseline == "copy" && c.source == "model-mean") {
      EXPECT_EQ(c.difference, 0.0);
      EXPECT_EQ(c.paired_sd, 0.0);
      EXPECT_EQ(c.wins, 0);
      continue;
    }
    // model-mean's windows are copy's: against the oracle it is copy.
    const std::vector<double>& o_runs = band < 0 ? oracle.macro_f1 : oracle.band_f1[std::size_t(band)];
    const std::vector<double>& c_runs = band < 0 ? copy.macro_f1 : copy.band_f1[std::size_t(band)];
    const double headroom = ((o_runs[0] - c_runs[0]) + (o_runs[1] - c_runs[1])) / 2;
    EXPECT_NEAR(c.difference, c.source == "oracle" ? headroom : -headroom, 1e-12) << i;
  }
}

TEST(HarBench, ComparisonsAreRunByRun) {
  BenchSource a, b;
  a.name = "model";
  b.name = "copy";
  a.macro_f1 = {0.60, 0.50, 0.70};
  b.macro_f1 = {0.55, 0.46, 0.66};  // lower in every run by 0.04-0.05: a common seed effect
  const BenchComparison c = compare_runs(a, b);
  EXPECT_NEAR(c.difference, 0.13 / 3, 1e-12);
  const double m = 0.13 / 3;
  const double var = ((0.05 - m) * (0.05 - m) + 2 * (0.04 - m) * (0.04 - m)) / 2;
  EXPECT_NEAR(c.paired_sd, std::sqrt(var), 1e-12);
  // The larger of the two sources' sample sd over runs: b's (mean 1.67 / 3).
  const double mb = 1.67 / 3;
  const double var_b = ((0.55 - mb) * (0.55 - mb) + (0.46 - mb) * (0.46 - mb) + (0.66 - mb) * (0.66 - mb)) / 2;
  EXPECT_NEAR(c.run_sd, std::sqrt(var_b), 1e-12);
  EXPECT_GT(var_b, 0.01) << "b's sd exceeds a's (0.1)";
  EXPECT_EQ(c.wins, 3);
  b.macro_f1.pop_back();
  EXPECT_NE(error_of([&] { compare_runs(a, b); }).find("cannot compare 3 runs of model with 2 of copy"),
            std::string::npos);
}


TEST(HarBench, ComparisonsPrintTheirBandAndRunsWonOutOfRuns) {
  BenchResult r;
  r.runs = 10;
  BenchTable t;
  t.labels = "activity";
  t.comparisons.push_back({"model", "copy", "", 0.02, 0.01, 0.02, 9});
  t.comparisons.push_back({"model", "copy", "xlarge", 0.04, 0.02, 0.02, 10});
  r.tables.push_back(t);
  const std::string text = format_bench(r);
  EXPECT_NE(text.find("  model - copy: +0.020 (2.0 paired sd; higher in 9 of 10 runs; 1.0 run sd)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("  [xlarge] model - copy: +0.040 (2.0 paired sd; higher in 10 of 10 runs; 2.0 run sd)"),
            std::string::npos)
      << text;
}
