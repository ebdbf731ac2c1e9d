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

#include "har/har_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::har {
namespace {

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
  // Paper section 3.1 (ptnet/paper.hpp), sexes alternating, through the
  // project's own Gaussian: the same bodies with every standard library.
  std::mt19937_64 rng(seed);
  std::vector<BodySpec> out;
  for (int i = 0; i < count; ++i)
    out.push_back(draw_paper_body(rng, i % 2 == 0 ? Sex::female : Sex::male, "syn" + std::to_string(i + 1),
                                  "retargeted"));
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

namespace {

// ---- the phases of validate_har(), in order

void say(const HarOptions& o, const std::string& line) {
  if (o.progress) o.progress(progress_line("har", line));
}

void check_options(const TransferFn& transfer, const HarOptions& o) {
  if (o.runs < 1) throw Error("har: runs must be at least 1, found " + std::to_string(o.runs));
  if (o.stride < 1) throw Error("har: stride must be at least 1, found " + std::to_string(o.stride));
  if (!transfer) throw Error("har: no transfer function given");
}

// The real windows of both subject sets.
struct RealWindows {
  WindowSet train, test;
  std::vector<int> train_sequences;  // indices into Dataset::sequences() of the training subjects
  int count() const { return train.count() + test.count(); }
};

RealWindows read_real_windows(const Dataset& real, const HarOptions& o, HarResult& r) {
  const double fps = real.info().fps;
  const auto& sequences = real.sequences();
  RealWindows w;
  for (int pass = 0; pass < 2; ++pass) {
    const auto& subjects = pass == 0 ? r.train_subjects : r.test_subjects;
    WindowSet& set = pass == 0 ? w.train : w.test;
    for (const std::string& subject : subjects) {
      for (int i = 0; i < int(sequences.size()); ++i) {
        if (sequences[i].body_id != subject) continue;
        if (sequences[i].frames < kWindowFrames) continue;
        const PressureSequence seq = real.read(sequences[i].name);
        add_windows(seq, i, sequences[i].category, o.stride, o.input, fps, set);
        if (pass == 0) w.train_sequences.push_back(i);
      }
    }
  }
  r.train_windows = w.train.count();
  r.test_windows = w.test.count();
  say(o, "har: " + std::to_string(r.train_windows) + " training windows (subjects " + join(r.train_subjects) +
             "), " + std::to_string(r.test_windows) + " test windows (subjects " + join(r.test_subjects) + ")");
  return w;
}

// Per cluster, the features furthest from the median window: mean robust z
// over the cluster's windows, the kClusterFeatures largest |z| first.
// features [N, F] (robust-standardised), labels [N] in [0, C).
std::vector<std::vector<std::pair<std::string, double>>> cluster_profiles(const Eigen::MatrixXd& features,
                                                                          const std::vector<int>& labels,
                                                                          int clusters) {
  constexpr int kClusterFeatures = 4;  // features named per cluster
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(clusters, features.cols());
  std::vector<int> count(clusters, 0);
  for (int i = 0; i < int(labels.size()); ++i) {
    sum.row(labels[i]) += features.row(i);
    ++count[labels[i]];
  }
  std::vector<std::vector<std::pair<std::string, double>>> out(clusters);
  for (int c = 0; c < clusters; ++c) {
    std::vector<std::pair<std::string, double>> all;
    for (int j = 0; j < features.cols(); ++j)
      all.emplace_back(feature_names()[j], count[c] ? sum(c, j) / count[c] : 0.0);
    std::stable_sort(all.begin(), all.end(),
                     [](const auto& a, const auto& b) { return std::fabs(a.second) > std::fabs(b.second); });
    all.resize(std::min<std::size_t>(all.size(), kClusterFeatures));
    out[c] = all;
  }
  return out;
}

// Pseudo labels: robust standardise + PCA + mean shift on all real windows, train
// windows first: [N].
std::vector<int> pseudo_labels(const Dataset& real, const RealWindows& w, const HarOptions& o, HarResult& r) {
  const int n_all = w.count();
  const int nf = int(feature_names().size());
  Eigen::MatrixXd features(n_all, nf);
  for (int i = 0; i < n_all; ++i) {
    const auto& f = i < w.train.count() ? w.train.features[i] : w.test.features[i - w.train.count()];
    for (int j = 0; j < nf; ++j) features(i, j) = f[j];
  }
  normalise_per_subject(features, window_subjects(real, w.train, w.test));
  robust_standardise(features);
  const int k = std::clamp(o.pca_components, 1, nf);
  const Pca pca = Pca::fit(features, k);
  const MeanShiftResult ms = mean_shift(pca.transform(features), o.mean_shift);
  r.pca_components = k;
  r.pca_explained = pca.explained;
  r.bandwidth = ms.bandwidth;
  r.bandwidth_estimated = !(o.mean_shift.bandwidth > 0);
  r.bandwidth_quantile = ms.quantile;
  r.bandwidth_candidates = ms.candidates;
  r.silhouette = ms.silhouette;
  r.clusters = ms.clusters();
  r.cluster_sizes = ms.sizes;
  r.cluster_features = cluster_profiles(features, ms.labels, r.clusters);
  std::ostringstream s;
  s << "har: mean shift: " << r.clusters << " clusters, bandwidth " << r.bandwidth;
  if (r.bandwidth_estimated) s << " (estimated: quantile " << r.bandwidth_quantile << ", best silhouette)";
  else s << " (given)";
  s << ", silhouette " << fixed_text(r.silhouette) << ", PCA " << k << " components ("
    << int(std::round(100 * pca.explained)) << " % of variance), " << ms.seeds << " seeds";
  say(o, s.str());
  if (r.clusters < 2)
    throw Error::in(real.path(), "mean shift found a single cluster (bandwidth " +
                                     std::to_string(r.bandwidth) + "); pass a smaller " +
                                     field_text("bandwidth"));
  return ms.labels;
}

// The labels of the training and test windows: pseudo labels, and category
// indices where every window has a category.
struct Labels {
  std::vector<int> train, test;          // pseudo labels
  std::vector<int> train_cat, test_cat;  // categories (empty: unlabelled data)
  bool use_categories = false;           // also train and score category classifiers
};

Labels split_labels(const RealWindows& w, const std::vector<int>& labels, const HarOptions& o, HarResult& r) {
  const WindowSet &train = w.train, &test = w.test;
  Labels l;
  l.train.assign(labels.begin(), labels.begin() + train.count());
  l.test.assign(labels.begin() + train.count(), labels.end());
  std::set<std::string> category_set(train.category.begin(), train.category.end());
  category_set.insert(test.category.begin(), test.category.end());
  category_set.erase("");
  r.categories.assign(category_set.begin(), category_set.end());
  auto category_index = [&](const std::string& c) {
    return int(std::lower_bound(r.categories.begin(), r.categories.end(), c) - r.categories.begin());
  };
  auto none_empty = [](const std::vector<std::string>& v) {
    return std::none_of(v.begin(), v.end(), [](const std::string& c) { return c.empty(); });
  };
  const bool all_labelled = none_empty(train.category) && none_empty(test.category);
  l.use_categories = o.category_labels && all_labelled && r.categories.size() >= 2;
  if (r.categories.empty() || !all_labelled) return l;
  r.cluster_vs_category = Eigen::MatrixXi::Zero(r.clusters, int(r.categories.size()));
  for (int i = 0; i < w.count(); ++i) {
    const std::string& c = i < train.count() ? train.category[i] : test.category[i - train.count()];
    ++r.cluster_vs_category(labels[i], category_index(c));
  }
  for (const auto& c : train.category) l.train_cat.push_back(category_index(c));
  for (const auto& c : test.category) l.test_cat.push_back(category_index(c));
  std::vector<int> all_cat = l.train_cat;
  all_cat.insert(all_cat.end(), l.test_cat.begin(), l.test_cat.end());
  r.cluster_purity = cluster_purity(labels, all_cat);
  r.cluster_ari = adjusted_rand_index(labels, all_cat);
  return l;
}

// Synthetic windows: the training subjects' sequences transferred onto new
// bodies, each window with the labels of the real window it came from.
struct SyntheticWindows {
  PreparedWindows inputs;
  std::vector<int> labels, categories;
};

SyntheticWindows transfer_windows(const Dataset& real, const TransferFn& transfer, const RealWindows& w,
                                  const Labels& l, const HarOptions& o, HarResult& r) {
  r.synthetic_bodies = o.bodies.empty() ? sample_paper_bodies(o.synthetic_bodies, o.seed) : o.bodies;
  const auto& sequences = real.sequences();
  std::map<std::pair<int, int>, int> window_index;  // (sequence, start) -> training window
  for (int i = 0; i < w.train.count(); ++i) window_index[{w.train.sequence[i], w.train.start[i]}] = i;
  SyntheticWindows syn;
  int done = 0;
  for (int si : w.train_sequences) {
    const SequenceMeta& meta = sequences[si];
    const PressureSequence source = real.read(meta.name);
    const BodySpec& from = real.body(meta.body_id);
    for (const BodySpec& to : r.synthetic_bodies) {
      const PressureSequence out = transfer(source, from, to);
      if (!(out.mat == source.mat) || out.frames() != source.frames())
        throw Error("har: transfer of " + meta.name + " returned " + std::to_string(out.frames()) + " frames of " +
                    std::to_string(out.mat.rows) + "x" + std::to_string(out.mat.cols) + ", expected " +
                    std::to_string(source.frames()) + " of " + std::to_string(source.mat.rows) + "x" +
                    std::to_string(source.mat.cols));
      for (int t : window_starts(out.frames(), o.stride)) {
        const int i = window_index.at({si, t});
        prepare_window(out.kpa.data() + std::size_t(t) * out.mat.cells(), kWindowFrames, out.mat, o.input,
                       syn.inputs);
        syn.labels.push_back(l.train[i]);
        if (!l.train_cat.empty()) syn.categories.push_back(l.train_cat[i]);
      }
    }
    ++done;
    say(o, "har: transferred " + std::to_string(done) + "/" + std::to_string(w.train_sequences.size()) +
               " training sequences onto " + std::to_string(r.synthetic_bodies.size()) + " bodies");
  }
  return syn;
}

// One training source of the classifiers: its windows and their labels.
struct TrainingSource {
  std::string name;
  const PreparedWindows* inputs;
  std::vector<int> labels, categories;
};

std::vector<int> concat(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// `o.runs` seeded classifiers trained on one source, scored on the test windows.
SourceResult score_source(const TrainingSource& s, const WindowSet& test, const Labels& l, const HarOptions& o,
                          const HarResult& r) {
  const int ncat = int(r.categories.size());
  SourceResult sr;
  sr.source = s.name;
  sr.train_windows = s.inputs->count();
  sr.confusion = Eigen::MatrixXi::Zero(r.clusters, r.clusters);
  sr.class_f1_mean.assign(r.clusters, 0.0);
  if (l.use_categories) sr.category_confusion = Eigen::MatrixXi::Zero(ncat, ncat);
  for (int run = 0; run < o.runs; ++run) {
    ClassifierOptions co = o.classifier;
    co.seed = o.classifier.seed + std::uint64_t(run);
    WindowClassifier net(s.inputs->channels, s.inputs->rows, s.inputs->cols, r.clusters, co);
    net.train(*s.inputs, s.labels);
    const ClassificationReport rep = classification_report(l.test, net.predict(test.inputs), r.clusters);
    sr.macro_f1.push_back(rep.macro_f1);
    sr.accuracy.push_back(rep.accuracy);
    sr.confusion += rep.confusion;
    for (int c = 0; c < r.clusters; ++c) sr.class_f1_mean[c] += rep.f1[c] / o.runs;
    std::ostringstream line;
    line.precision(3);
    line << std::fixed << "har: [" << s.name << " run " << run + 1 << "/" << o.runs << "] macro F1 "
         << rep.macro_f1 << " accuracy " << rep.accuracy;
    if (l.use_categories) {
      WindowClassifier cat(s.inputs->channels, s.inputs->rows, s.inputs->cols, ncat, co);
      cat.train(*s.inputs, s.categories);
      const ClassificationReport cr = classification_report(l.test_cat, cat.predict(test.inputs), ncat);
      sr.category_macro_f1.push_back(cr.macro_f1);
      sr.category_confusion += cr.confusion;
      line << " category macro F1 " << cr.macro_f1;
    }
    say(o, line.str());
  }
  sr.macro_f1_mean = mean_of(sr.macro_f1);
  sr.macro_f1_std = sd_of(sr.macro_f1);
  sr.accuracy_mean = mean_of(sr.accuracy);
  sr.category_macro_f1_mean = mean_of(sr.category_macro_f1);
  sr.category_macro_f1_std = sd_of(sr.category_macro_f1);
  return sr;
}

// Classifiers per training source: real, synthetic, real + synthetic.
void score_sources(const RealWindows& w, const Labels& l, const SyntheticWindows& syn, const HarOptions& o,
                   HarResult& r) {
  PreparedWindows both = w.train.inputs;
  both.append(syn.inputs);
  const std::vector<TrainingSource> sources = {
      {"real", &w.train.inputs, l.train, l.train_cat},
      {"synthetic", &syn.inputs, syn.labels, syn.categories},
      {"real+synthetic", &both, concat(l.train, syn.labels), concat(l.train_cat, syn.categories)}};
  for (const TrainingSource& s : sources) r.sources.push_back(score_source(s, w.test, l, o, r));
}

}  // namespace

HarResult validate_har(const Dataset& real, const TransferFn& transfer, const HarOptions& o) {
  const auto t_begin = std::chrono::steady_clock::now();
  check_options(transfer, o);
  HarResult r;
  r.dataset = real.path();
  std::tie(r.train_subjects, r.test_subjects) = check_subjects(real, o);
  r.runs = o.runs;
  r.stride = o.stride;
  const RealWindows windows = read_real_windows(real, o, r);
  const Labels labels = split_labels(windows, pseudo_labels(real, windows, o, r), o, r);
  const SyntheticWindows synthetic = transfer_windows(real, transfer, windows, labels, o, r);
  score_sources(windows, labels, synthetic, o, r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return r;
}

}  // namespace ptnet::har
