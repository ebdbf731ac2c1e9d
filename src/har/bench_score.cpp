// The body-shift HAR benchmark's scoring (bench_internal.hpp): every
// training source's classifiers trained and scored on the deployment test
// windows, the table of sources, the paired comparisons and the gap.
//
// Dimension legend: N test windows, C classes, D deployment bodies.
#include <algorithm>
#include <atomic>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>

#include "bench_internal.hpp"
#include "har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::har {
namespace {

// One run's outcome on the test windows.
struct RunScore {
  ClassificationReport report;
  std::vector<double> body_f1;  // [D]
  std::vector<double> band_f1;  // [deployment bands]
};

// Macro F1 over the test windows whose deployment body passes `keep`.
template <class Keep>
double macro_f1_where(const Windows& test, const std::vector<int>& truth, const std::vector<int>& predicted,
                      int classes, Keep keep) {
  std::vector<int> t, p;
  for (int i = 0; i < test.count(); ++i)
    if (keep(test.body[std::size_t(i)])) {
      t.push_back(truth[std::size_t(i)]);
      p.push_back(predicted[std::size_t(i)]);
    }
  return t.empty() ? 0.0 : classification_report(t, p, classes).macro_f1;
}

// A run's ensemble: its members' probabilities [N x C] averaged, scored on
// the test windows overall, per deployment body and per deployment band
// (body d is of band d / bodies_per_band).
RunScore score_run(const std::vector<const std::vector<float>*>& members, const Windows& test,
                   const std::vector<int>& truth, int classes, int deployment_bodies, const BenchOptions& o) {
  std::vector<float> mean(members.front()->size(), 0.0f);
  for (const std::vector<float>* m : members)
    for (std::size_t i = 0; i < mean.size(); ++i) mean[i] += (*m)[i] / float(members.size());
  const std::vector<int> predicted = argmax_rows(mean, classes);
  RunScore r{classification_report(truth, predicted, classes), {}, {}};
  for (int d = 0; d < deployment_bodies; ++d)
    r.body_f1.push_back(macro_f1_where(test, truth, predicted, classes, [d](int body) { return body == d; }));
  for (int b = 0; b < int(o.deployment_bands.size()); ++b)
    r.band_f1.push_back(macro_f1_where(test, truth, predicted, classes,
                                       [&](int body) { return body / o.bodies_per_band == b; }));
  return r;
}

// Runs task(i) for i in [0, n) on `workers` threads; the first error is rethrown.
void run_tasks(int n, int workers, const std::function<void(int)>& task) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    for (int i = next++; i < n; i = next++) {
      try {
        task(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = n;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int w = 1; w < std::min(workers, n); ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

// Every classifier of every source trained on its windows: the test
// windows' probabilities [source, run, member][N x C].
std::vector<std::vector<float>> train_classifiers(const std::vector<Synthesis>& sources, const Windows& recorded,
                                                  const Windows& test, bool pseudo, int classes,
                                                  const BenchOptions& o) {
  const int ns = int(sources.size());
  const std::vector<int>& truth = pseudo ? test.pseudo : test.activity;
  const std::string labels_name = pseudo ? "pseudo" : "activity";
  std::vector<PreparedWindows> inputs(std::size_t(ns), recorded.inputs);
  std::vector<std::vector<int>> labels(std::size_t(ns), pseudo ? recorded.pseudo : recorded.activity);
  for (int s = 0; s < ns; ++s) {
    const Windows& extra = sources[std::size_t(s)].extra;
    if (extra.count() == 0) continue;
    inputs[std::size_t(s)].append(extra.inputs);
    const std::vector<int>& more = pseudo ? extra.pseudo : extra.activity;
    labels[std::size_t(s)].insert(labels[std::size_t(s)].end(), more.begin(), more.end());
  }
  const int workers = o.workers > 0 ? o.workers : int(std::max(1u, std::thread::hardware_concurrency()));
  const int members = o.runs * o.ensemble;  // classifiers per source
  std::vector<std::vector<float>> probabilities(std::size_t(ns * members));
  std::mutex say_mutex;
  int done = 0;
  run_tasks(ns * members, workers, [&](int i) {
    const int s = i / members, member = i % members;
    const PreparedWindows& x = inputs[std::size_t(s)];
    ClassifierOptions co = o.classifier;
    co.seed = o.classifier.seed + std::uint64_t(member);
    if (workers > 1) co.threads = 1;
    WindowClassifier net(x.channels, x.rows, x.cols, classes, co);
    net.train(x, labels[std::size_t(s)]);
    probabilities[std::size_t(i)] = net.probabilities(test.inputs);
    const double f1 = classification_report(truth, argmax_rows(probabilities[std::size_t(i)], classes), classes).macro_f1;
    const std::lock_guard<std::mutex> lock(say_mutex);
    say(o, "har-bench: [" + labels_name + " labels " + std::to_string(++done) + "/" + std::to_string(ns * members) +
               "] " + sources[std::size_t(s)].name + " run " + std::to_string(member / o.ensemble + 1) +
               (o.ensemble > 1 ? " member " + std::to_string(member % o.ensemble + 1) : "") + ": macro F1 " +
               fixed_text(f1));
  });
  return probabilities;
}

// One source's row: its runs' scores gathered.
BenchSource source_row(const std::string& name, int train_windows, const std::vector<RunScore>& runs, int classes,
                       int deployment_bodies, const BenchOptions& o) {
  BenchSource r;
  r.name = name;
  r.train_windows = train_windows;
  r.class_f1.assign(std::size_t(classes), 0.0);
  r.body_f1.assign(std::size_t(deployment_bodies), {});
  r.band_f1.assign(o.deployment_bands.size(), {});
  r.confusion = Eigen::MatrixXi::Zero(classes, classes);
  for (const RunScore& x : runs) {
    r.macro_f1.push_back(x.report.macro_f1);
    r.confusion += x.report.confusion;
    for (int c = 0; c < classes; ++c) r.class_f1[std::size_t(c)] += x.report.f1[std::size_t(c)] / double(runs.size());
    for (int d = 0; d < deployment_bodies; ++d) r.body_f1[std::size_t(d)].push_back(x.body_f1[std::size_t(d)]);
    for (std::size_t b = 0; b < x.band_f1.size(); ++b) r.band_f1[b].push_back(x.band_f1[b]);
  }
  r.mean = mean_of(r.macro_f1);
  r.sd = sd_of(r.macro_f1);
  return r;
}

// The whole deployment population, then (with 2+ bands) band by band: every
// transfer against every baseline and against the oracle; the oracle against
// every baseline (the largest margin a perfect transfer would show: the
// benchmark's headroom). Then the gap and the share of it each source closes.
void compare_sources(BenchTable& t, const BenchOptions& o) {
  if (o.deployment_bands.size() > 1) t.bands = o.deployment_bands;
  const auto compared = [](const std::string& a, const std::string& b) {
    return (is_transfer_source(a) && (is_baseline(b) || b == "oracle")) || (a == "oracle" && is_baseline(b));
  };
  for (int band = -1; band < int(t.bands.size()); ++band)
    for (const BenchSource& a : t.sources)
      for (const BenchSource& b : t.sources)
        if (compared(a.name, b.name)) {
          if (band < 0) {
            t.comparisons.push_back(compare_runs(a, b));
            continue;
          }
          BenchComparison c = compare_runs(a.name, a.band_f1[std::size_t(band)], b.name, b.band_f1[std::size_t(band)]);
          c.band = t.bands[std::size_t(band)];
          t.comparisons.push_back(c);
        }
  const double floor = t.sources.front().mean, ceiling = t.sources.back().mean;
  t.gap = ceiling - floor;
  for (std::size_t i = 0; i < t.sources.size(); ++i)
    t.sources[i].gap_closed = i == 0 || i + 1 == t.sources.size() || t.gap == 0
                                  ? std::numeric_limits<double>::quiet_NaN()
                                  : (t.sources[i].mean - floor) / t.gap;
}

}  // namespace

BenchTable score_table(const std::vector<Synthesis>& sources, const Windows& recorded, const Windows& test,
                       bool pseudo, const std::vector<std::string>& classes, int deployment_bodies,
                       const BenchOptions& o) {
  BenchTable t;
  t.labels = pseudo ? "pseudo" : "activity";
  t.classes = classes;
  const int nc = int(classes.size()), ns = int(sources.size());
  const std::vector<int>& truth = pseudo ? test.pseudo : test.activity;
  t.test_support.assign(std::size_t(nc), 0);
  for (int l : truth) ++t.test_support[std::size_t(l)];
  const std::vector<std::vector<float>> probabilities = train_classifiers(sources, recorded, test, pseudo, nc, o);
  const int members = o.runs * o.ensemble;
  for (int s = 0; s < ns; ++s) {
    std::vector<RunScore> runs;
    for (int run = 0; run < o.runs; ++run) {
      std::vector<const std::vector<float>*> ensemble;
      for (int k = 0; k < o.ensemble; ++k)
        ensemble.push_back(&probabilities[std::size_t(s * members + run * o.ensemble + k)]);
      runs.push_back(score_run(ensemble, test, truth, nc, deployment_bodies, o));
    }
    const int train_windows = recorded.count() + sources[std::size_t(s)].extra.count();
    t.sources.push_back(source_row(sources[std::size_t(s)].name, train_windows, runs, nc, deployment_bodies, o));
  }
  compare_sources(t, o);
  return t;
}

BenchComparison compare_runs(const std::string& source, const std::vector<double>& source_f1,
                             const std::string& baseline, const std::vector<double>& baseline_f1) {
  if (source_f1.size() != baseline_f1.size() || source_f1.empty())
    throw Error("har-bench: cannot compare " + std::to_string(source_f1.size()) + " runs of " + source + " with " +
                std::to_string(baseline_f1.size()) + " of " + baseline);
  BenchComparison c{source, baseline, "", 0, 0, std::max(sd_of(source_f1), sd_of(baseline_f1)), 0};
  std::vector<double> d;
  for (std::size_t run = 0; run < source_f1.size(); ++run) {
    d.push_back(source_f1[run] - baseline_f1[run]);
    c.wins += d.back() > 0;
  }
  c.difference = mean_of(d);
  c.paired_sd = sd_of(d);
  return c;
}

BenchComparison compare_runs(const BenchSource& source, const BenchSource& baseline) {
  return compare_runs(source.name, source.macro_f1, baseline.name, baseline.macro_f1);
}

}  // namespace ptnet::har
