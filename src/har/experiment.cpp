// The validate-har experiment (ptnet/har.hpp, docs/har.md): pseudo labels by
// mean shift, synthetic windows by transfer, a classifier per training
// source and run, scored on the test subjects' real windows.
//
// Dimension legend: N windows, T = 30 frames, H x W mat cells, C clusters.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <tuple>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {
namespace {

// Paper section 3.1: ten males 175 +- 15 cm, 75 +- 10 kg; ten females
// 165 +- 15 cm, 65 +- 10 kg, Gaussian.
constexpr double kMaleHeightCm = 175, kFemaleHeightCm = 165, kHeightSdCm = 15;
constexpr double kMaleWeightKg = 75, kFemaleWeightKg = 65, kWeightSdKg = 10;

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

// Real windows of a set of subjects, with everything the experiment needs.
struct WindowSet {
  PreparedWindows inputs;          // [N, B, H', W']
  std::vector<std::vector<double>> features;  // [N][F]
  std::vector<std::string> category;          // [N]
  std::vector<int> sequence;       // [N] index into Dataset::sequences()
  std::vector<int> start;          // [N] first frame
  int count() const { return int(start.size()); }
};

std::vector<int> window_starts(int frames, int stride) {
  std::vector<int> s;
  for (int t = 0; t + kWindowFrames <= frames; t += stride) s.push_back(t);
  return s;
}

void add_windows(const PressureSequence& seq, int sequence_index, const std::string& category,
                 int stride, const InputOptions& input, double fps, WindowSet& out) {
  const std::size_t cells = seq.mat.cells();
  for (int t : window_starts(seq.frames(), stride)) {
    const float* w = seq.kpa.data() + std::size_t(t) * cells;
    out.features.push_back(window_feature_vector(w, kWindowFrames, seq.mat, fps));
    prepare_window(w, kWindowFrames, seq.mat, input, out.inputs);
    out.category.push_back(category);
    out.sequence.push_back(sequence_index);
    out.start.push_back(t);
  }
}

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

// Sample standard deviation (n - 1); 0 for one value.
double sd_of(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size() - 1));
}

// Body id of every window, train windows first: [N].
std::vector<std::string> window_subjects(const Dataset& real, const WindowSet& train,
                                         const WindowSet& test) {
  std::vector<std::string> out;
  for (const WindowSet* set : {&train, &test})
    for (int s : set->sequence) out.push_back(real.sequences()[s].body_id);
  return out;
}

}  // namespace

// Features that scale with the body (force with weight, contact area and
// peak pressure with foot size) are divided by the subject's median over
// its windows, so that clusters follow activities rather than bodies.
void normalise_per_subject(Eigen::MatrixXd& features, const std::vector<std::string>& subject) {
  static const std::vector<std::string> scaled = {"force_mean_n",   "area_mean_cells",
                                                  "area_sd_cells",  "area_min_cells",
                                                  "area_max_cells", "peak_mean_kpa",
                                                  "peak_max_kpa"};
  if (int(subject.size()) != features.rows())
    throw Error("har: " + std::to_string(subject.size()) + " subjects for " +
                std::to_string(features.rows()) + " windows");
  const auto& names = feature_names();
  std::map<std::string, std::vector<int>> rows;
  for (int i = 0; i < int(subject.size()); ++i) rows[subject[i]].push_back(i);
  for (const std::string& name : scaled) {
    const int j = int(std::find(names.begin(), names.end(), name) - names.begin());
    if (j >= features.cols()) continue;
    for (const auto& [who, idx] : rows) {
      std::vector<double> v;
      for (int i : idx) v.push_back(features(i, j));
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      const double median = v[v.size() / 2];
      if (median > 0)
        for (int i : idx) features(i, j) /= median;
    }
  }
}

std::vector<BodySpec> sample_paper_bodies(int count, std::uint64_t seed) {
  if (count < 1) throw Error("har: need at least one synthetic body, found " + std::to_string(count));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<BodySpec> out;
  for (int i = 0; i < count; ++i) {
    BodySpec b;
    b.id = "syn" + std::to_string(i + 1);
    b.sex = i % 2 == 0 ? Sex::female : Sex::male;
    const bool male = b.sex == Sex::male;
    const double h = (male ? kMaleHeightCm : kFemaleHeightCm) + kHeightSdCm * unit(rng);
    const double w = (male ? kMaleWeightKg : kFemaleWeightKg) + kWeightSdKg * unit(rng);
    b.height_cm = std::round(std::clamp(h, kMinHeightCm, kMaxHeightCm) * 10) / 10;
    b.weight_kg = std::round(std::clamp(w, kMinWeightKg, kMaxWeightKg) * 10) / 10;
    b.role = "retargeted";
    out.push_back(b);
  }
  return out;
}

std::string resolve_subject(const Dataset& data, const std::string& token) {
  for (const std::string& id : {token, "s" + token, "subject" + token})
    for (const BodySpec& b : data.bodies())
      if (b.id == id) return b.id;
  std::vector<std::string> ids;
  for (const BodySpec& b : data.bodies()) ids.push_back(b.id);
  throw Error::in(data.path(), "no subject '" + token + "' (bodies: " + join(ids) + ")");
}

std::pair<std::vector<std::string>, std::vector<std::string>> check_subjects(
    const Dataset& real, const HarOptions& o) {
  const std::string& path = real.path();
  if (o.train_subjects.empty()) throw Error::in(path, "no training subjects given");
  if (o.test_subjects.empty()) throw Error::in(path, "no test subjects given");
  std::vector<std::string> train, test;
  for (const auto& s : o.train_subjects) train.push_back(resolve_subject(real, s));
  for (const auto& s : o.test_subjects) test.push_back(resolve_subject(real, s));
  std::set<std::string> seen;
  for (const auto& s : train)
    if (!seen.insert(s).second) throw Error::in(path, "subject " + s + " listed twice for training");
  for (const auto& s : test) {
    if (std::count(train.begin(), train.end(), s))
      throw Error::in(path, "subject " + s + " is in both the training and the test subjects");
    if (!seen.insert(s).second) throw Error::in(path, "subject " + s + " listed twice for testing");
  }
  for (const auto& s : seen) {
    bool ok = false;
    for (const auto& q : real.sequences()) ok = ok || (q.body_id == s && q.frames >= kWindowFrames);
    if (!ok)
      throw Error::in(path, "subject " + s + " has no sequence of at least " +
                                std::to_string(kWindowFrames) + " frames");
  }
  return {train, test};
}

HarResult validate_har(const Dataset& real, const TransferFn& transfer, const HarOptions& o) {
  const auto t_begin = std::chrono::steady_clock::now();
  auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  const std::string& path = real.path();
  if (o.runs < 1) throw Error("har: runs must be at least 1, found " + std::to_string(o.runs));
  if (o.stride < 1) throw Error("har: stride must be at least 1, found " + std::to_string(o.stride));
  if (!transfer) throw Error("har: no transfer function given");

  HarResult r;
  r.dataset = path;
  std::tie(r.train_subjects, r.test_subjects) = check_subjects(real, o);
  r.runs = o.runs;
  r.stride = o.stride;

  // ---- real windows of both subject sets
  const double fps = real.info().fps;
  const auto& sequences = real.sequences();
  WindowSet train, test;
  std::vector<int> train_sequences;
  for (int pass = 0; pass < 2; ++pass) {
    const auto& subjects = pass == 0 ? r.train_subjects : r.test_subjects;
    WindowSet& set = pass == 0 ? train : test;
    for (const std::string& subject : subjects) {
      for (int i = 0; i < int(sequences.size()); ++i) {
        if (sequences[i].body_id != subject) continue;
        if (sequences[i].frames < kWindowFrames) continue;
        const PressureSequence seq = real.read(sequences[i].name);
        add_windows(seq, i, sequences[i].category, o.stride, o.input, fps, set);
        if (pass == 0) train_sequences.push_back(i);
      }
    }
  }
  r.train_windows = train.count();
  r.test_windows = test.count();
  say("har: " + std::to_string(r.train_windows) + " training windows (subjects " +
      join(r.train_subjects) + "), " + std::to_string(r.test_windows) + " test windows (subjects " +
      join(r.test_subjects) + ")");

  // ---- pseudo labels: standardise + PCA + mean shift on all real windows
  const int n_all = train.count() + test.count();
  const int nf = int(feature_names().size());
  Eigen::MatrixXd features(n_all, nf);
  for (int i = 0; i < n_all; ++i) {
    const auto& f = i < train.count() ? train.features[i] : test.features[i - train.count()];
    for (int j = 0; j < nf; ++j) features(i, j) = f[j];
  }
  normalise_per_subject(features, window_subjects(real, train, test));
  const int k = std::clamp(o.pca_components, 1, nf);
  const Pca pca = Pca::fit(features, k);
  const Eigen::MatrixXd z = pca.transform(features);
  const MeanShiftResult ms = mean_shift(z, o.mean_shift);
  r.pca_components = k;
  r.pca_explained = pca.explained;
  r.bandwidth = ms.bandwidth;
  r.bandwidth_estimated = !(o.mean_shift.bandwidth > 0);
  r.clusters = ms.clusters();
  r.cluster_sizes = ms.sizes;
  {
    std::ostringstream s;
    s << "har: mean shift: " << r.clusters << " clusters, bandwidth " << r.bandwidth
      << (r.bandwidth_estimated ? " (estimated)" : " (given)") << ", PCA " << k << " components ("
      << int(std::round(100 * pca.explained)) << " % of variance), " << ms.seeds << " seeds";
    say(s.str());
  }
  if (r.clusters < 2)
    throw Error::in(path, "mean shift found a single cluster (bandwidth " +
                              std::to_string(r.bandwidth) + "); pass a smaller --bandwidth");
  std::vector<int> train_labels(ms.labels.begin(), ms.labels.begin() + train.count());
  std::vector<int> test_labels(ms.labels.begin() + train.count(), ms.labels.end());

  // Category labels, where the dataset has them.
  std::set<std::string> category_set(train.category.begin(), train.category.end());
  category_set.insert(test.category.begin(), test.category.end());
  category_set.erase("");
  r.categories.assign(category_set.begin(), category_set.end());
  auto category_index = [&](const std::string& c) {
    return int(std::lower_bound(r.categories.begin(), r.categories.end(), c) - r.categories.begin());
  };
  const bool all_labelled =
      std::none_of(train.category.begin(), train.category.end(), [](auto& c) { return c.empty(); }) &&
      std::none_of(test.category.begin(), test.category.end(), [](auto& c) { return c.empty(); });
  const bool use_categories = o.category_labels && all_labelled && r.categories.size() >= 2;
  std::vector<int> train_cat, test_cat;
  if (!r.categories.empty() && all_labelled) {
    r.cluster_vs_category = Eigen::MatrixXi::Zero(r.clusters, int(r.categories.size()));
    for (int i = 0; i < n_all; ++i) {
      const std::string& c = i < train.count() ? train.category[i] : test.category[i - train.count()];
      ++r.cluster_vs_category(ms.labels[i], category_index(c));
    }
    long long majority = 0;
    for (int c = 0; c < r.clusters; ++c) majority += r.cluster_vs_category.row(c).maxCoeff();
    r.cluster_purity = double(majority) / double(n_all);
    for (const auto& c : train.category) train_cat.push_back(category_index(c));
    for (const auto& c : test.category) test_cat.push_back(category_index(c));
  }

  // ---- synthetic windows: train-subject sequences transferred onto new bodies
  r.synthetic_bodies = o.bodies.empty() ? sample_paper_bodies(o.synthetic_bodies, o.seed) : o.bodies;
  PreparedWindows synthetic;
  std::vector<int> synthetic_labels, synthetic_cat;
  {
    // Pseudo label of each (sequence, start) of the training windows.
    std::map<std::pair<int, int>, int> window_index;
    for (int i = 0; i < train.count(); ++i) window_index[{train.sequence[i], train.start[i]}] = i;
    int done = 0;
    for (int si : train_sequences) {
      const SequenceMeta& meta = sequences[si];
      const PressureSequence source = real.read(meta.name);
      const BodySpec& from = real.body(meta.body_id);
      for (const BodySpec& to : r.synthetic_bodies) {
        const PressureSequence out = transfer(source, from, to);
        if (!(out.mat == source.mat) || out.frames() != source.frames())
          throw Error("har: transfer of " + meta.name + " returned " + std::to_string(out.frames()) +
                      " frames of " + std::to_string(out.mat.rows) + "x" +
                      std::to_string(out.mat.cols) + ", expected " +
                      std::to_string(source.frames()) + " of " + std::to_string(source.mat.rows) +
                      "x" + std::to_string(source.mat.cols));
        for (int t : window_starts(out.frames(), o.stride)) {
          const int w = window_index.at({si, t});
          prepare_window(out.kpa.data() + std::size_t(t) * out.mat.cells(), kWindowFrames, out.mat,
                         o.input, synthetic);
          synthetic_labels.push_back(train_labels[w]);
          if (!train_cat.empty()) synthetic_cat.push_back(train_cat[w]);
        }
      }
      ++done;
      say("har: transferred " + std::to_string(done) + "/" + std::to_string(train_sequences.size()) +
          " training sequences onto " + std::to_string(r.synthetic_bodies.size()) + " bodies");
    }
  }
  PreparedWindows both = train.inputs;
  both.append(synthetic);
  auto concat = [](std::vector<int> a, const std::vector<int>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };

  // ---- classifiers: source x run (x label kind)
  struct Source {
    std::string name;
    const PreparedWindows* inputs;
    std::vector<int> labels, categories;
  };
  const std::vector<Source> sources = {
      {"real", &train.inputs, train_labels, train_cat},
      {"synthetic", &synthetic, synthetic_labels, synthetic_cat},
      {"real+synthetic", &both, concat(train_labels, synthetic_labels),
       concat(train_cat, synthetic_cat)}};
  const int ncat = int(r.categories.size());
  for (const Source& s : sources) {
    SourceResult sr;
    sr.source = s.name;
    sr.train_windows = s.inputs->count();
    sr.confusion = Eigen::MatrixXi::Zero(r.clusters, r.clusters);
    sr.class_f1_mean.assign(r.clusters, 0.0);
    if (use_categories) sr.category_confusion = Eigen::MatrixXi::Zero(ncat, ncat);
    for (int run = 0; run < o.runs; ++run) {
      ClassifierOptions co = o.classifier;
      co.seed = o.classifier.seed + std::uint64_t(run);
      WindowClassifier net(s.inputs->channels, s.inputs->rows, s.inputs->cols, r.clusters, co);
      net.train(*s.inputs, s.labels);
      const ClassificationReport rep =
          classification_report(test_labels, net.predict(test.inputs), r.clusters);
      sr.macro_f1.push_back(rep.macro_f1);
      sr.accuracy.push_back(rep.accuracy);
      sr.confusion += rep.confusion;
      for (int c = 0; c < r.clusters; ++c) sr.class_f1_mean[c] += rep.f1[c] / o.runs;
      std::ostringstream line;
      line.precision(3);
      line << std::fixed << "har: [" << s.name << " run " << run + 1 << "/" << o.runs
           << "] macro F1 " << rep.macro_f1 << " accuracy " << rep.accuracy;
      if (use_categories) {
        WindowClassifier cat(s.inputs->channels, s.inputs->rows, s.inputs->cols, ncat, co);
        cat.train(*s.inputs, s.categories);
        const ClassificationReport cr =
            classification_report(test_cat, cat.predict(test.inputs), ncat);
        sr.category_macro_f1.push_back(cr.macro_f1);
        sr.category_confusion += cr.confusion;
        line << " category macro F1 " << cr.macro_f1;
      }
      say(line.str());
    }
    sr.macro_f1_mean = mean_of(sr.macro_f1);
    sr.macro_f1_std = sd_of(sr.macro_f1);
    sr.accuracy_mean = mean_of(sr.accuracy);
    sr.category_macro_f1_mean = mean_of(sr.category_macro_f1);
    sr.category_macro_f1_std = sd_of(sr.category_macro_f1);
    r.sources.push_back(std::move(sr));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return r;
}

}  // namespace ptnet::har
