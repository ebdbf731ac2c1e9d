// The Table-3 text and results.json of a HAR validation (ptnet/har.hpp).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::har {
namespace {

std::string pad(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : s + std::string(width - s.size(), ' ');
}

// (the body stage's sex_name() is not needed for this one word)
const char* sex_word(Sex s) { return s == Sex::male ? "male" : "female"; }

nlohmann::json matrix(const Eigen::MatrixXi& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

std::string source_title(const std::string& source) {
  return source == "real" ? "Real" : source == "synthetic" ? "Synthetic" : "Real+Synthetic";
}

std::string pseudo_label_summary(const HarResult& r) {
  std::ostringstream o;
  o << "mean shift on " << r.pca_components << " PCA components (" << fixed_text(100 * r.pca_explained, 1)
    << " % of variance), bandwidth " << fixed_text(r.bandwidth)
    << (r.bandwidth_estimated ? " (estimated: quantile " + fixed_text(r.bandwidth_quantile, 2) + ", best silhouette)"
                              : std::string(" (given)"))
    << ", " << r.clusters << " clusters, silhouette " << fixed_text(r.silhouette);
  return o.str();
}

std::string format_table(const HarResult& r) {
  std::ostringstream o;
  o << "HAR validation of " << r.dataset << ": train subjects " << join(r.train_subjects, ",") << " ("
    << r.train_windows << " windows), test subjects " << join(r.test_subjects, ",") << " ("
    << r.test_windows << " windows), stride " << r.stride << ", " << r.runs << " runs\n";
  o << "Pseudo labels: " << pseudo_label_summary(r) << "\n";
  if (!r.bandwidth_candidates.empty()) {
    o << "Bandwidth rule tried (quantile: bandwidth, clusters, silhouette):";
    for (const auto& c : r.bandwidth_candidates)
      o << " " << fixed_text(c.quantile, 2) << ": " << fixed_text(c.bandwidth) << ", " << c.clusters << ", "
        << (c.clusters > 1 ? fixed_text(c.silhouette) : std::string("-")) << ";";
    o << "\n";
  }
  o << "Synthetic: " << r.synthetic_bodies.size() << " bodies (";
  for (std::size_t i = 0; i < r.synthetic_bodies.size(); ++i) {
    const BodySpec& b = r.synthetic_bodies[i];
    o << (i ? "; " : "") << b.id << " " << sex_word(b.sex) << " " << fixed_text(b.height_cm, 1) << " cm "
      << fixed_text(b.weight_kg, 1) << " kg";
  }
  o << ")\n\n";
  const std::size_t w0 = 32, w = 17;
  o << pad("Training dataset source", w0);
  for (const auto& s : r.sources) o << "| " << pad(source_title(s.source), w);
  o << "\n" << std::string(w0, '-');
  for (std::size_t i = 0; i < r.sources.size(); ++i) o << "+" << std::string(w + 1, '-');
  o << "\n" << pad("Macro F1 score (pseudo labels)", w0);
  for (const auto& s : r.sources)
    o << "| " << pad(fixed_text(s.macro_f1_mean) + " +- " + fixed_text(s.macro_f1_std), w);
  o << "\n" << pad("Accuracy (pseudo labels)", w0);
  for (const auto& s : r.sources) o << "| " << pad(fixed_text(s.accuracy_mean), w);
  if (!r.sources.empty() && !r.sources[0].category_macro_f1.empty()) {
    o << "\n" << pad("Macro F1 score (categories)", w0);
    for (const auto& s : r.sources)
      o << "| " << pad(fixed_text(s.category_macro_f1_mean) + " +- " + fixed_text(s.category_macro_f1_std), w);
  }
  o << "\n" << pad("Training windows", w0);
  for (const auto& s : r.sources) o << "| " << pad(std::to_string(s.train_windows), w);
  o << "\n\nPer-class F1 (pseudo labels, mean over runs):\n";
  o << pad("cluster (windows)", w0);
  for (const auto& s : r.sources) o << "| " << pad(s.source, w);
  o << "\n";
  for (int c = 0; c < r.clusters; ++c) {
    std::string label = std::to_string(c) + " (" + std::to_string(r.cluster_sizes[c]) + ")";
    if (r.cluster_vs_category.rows() == r.clusters && !r.categories.empty()) {
      Eigen::Index best = 0;
      r.cluster_vs_category.row(c).maxCoeff(&best);
      label += " mostly " + r.categories[best];
    }
    o << pad(label, w0);
    for (const auto& s : r.sources) o << "| " << pad(fixed_text(s.class_f1_mean[c]), w);
    o << "\n";
  }
  if (!r.categories.empty())
    o << "Cluster purity against categories: " << fixed_text(r.cluster_purity) << ", adjusted Rand index "
      << fixed_text(r.cluster_ari) << "\n";
  if (!r.cluster_features.empty()) {
    o << "What separates the clusters (mean robust z of the features furthest from the median window):\n";
    for (int c = 0; c < int(r.cluster_features.size()); ++c) {
      o << "  " << c << ":";
      for (const auto& [name, z] : r.cluster_features[c]) o << " " << name << " " << (z >= 0 ? "+" : "") << fixed_text(z, 2);
      o << "\n";
    }
  }
  o << "Time: " << fixed_text(r.seconds, 1) << " s\n";
  return o.str();
}

std::string to_json(const HarResult& r) {
  using nlohmann::json;
  json j;
  j["dataset"] = r.dataset;
  j["train_subjects"] = r.train_subjects;
  j["test_subjects"] = r.test_subjects;
  j["runs"] = r.runs;
  j["stride"] = r.stride;
  j["train_windows"] = r.train_windows;
  j["test_windows"] = r.test_windows;
  j["features"] = feature_names();
  j["pca"] = {{"components", r.pca_components}, {"explained_variance", r.pca_explained}};
  json tried = json::array();
  for (const auto& c : r.bandwidth_candidates)
    tried.push_back({{"quantile", c.quantile}, {"bandwidth", c.bandwidth}, {"clusters", c.clusters},
                     {"silhouette", c.silhouette}});
  json profiles = json::array();
  for (const auto& features : r.cluster_features) {
    json p = json::array();
    for (const auto& [name, z] : features) p.push_back({{"feature", name}, {"robust_z", z}});
    profiles.push_back(p);
  }
  j["mean_shift"] = {{"bandwidth", r.bandwidth},
                     {"bandwidth_estimated", r.bandwidth_estimated},
                     {"quantile", r.bandwidth_quantile},
                     {"candidates", tried},
                     {"silhouette", r.silhouette},
                     {"clusters", r.clusters},
                     {"cluster_sizes", r.cluster_sizes},
                     {"cluster_features", profiles}};
  json bodies = json::array();
  for (const auto& b : r.synthetic_bodies)
    bodies.push_back({{"id", b.id}, {"sex", sex_word(b.sex)}, {"height_cm", b.height_cm},
                      {"weight_kg", b.weight_kg}});
  j["synthetic_bodies"] = bodies;
  if (!r.categories.empty()) {
    j["categories"] = r.categories;
    j["cluster_vs_category"] = matrix(r.cluster_vs_category);
    j["cluster_purity"] = r.cluster_purity;
    j["cluster_adjusted_rand_index"] = r.cluster_ari;
  }
  json sources = json::array();
  for (const auto& s : r.sources) {
    json x;
    x["source"] = s.source;
    x["train_windows"] = s.train_windows;
    x["macro_f1"] = {{"mean", s.macro_f1_mean}, {"std", s.macro_f1_std}, {"runs", s.macro_f1}};
    x["accuracy"] = {{"mean", s.accuracy_mean}, {"runs", s.accuracy}};
    x["class_f1_mean"] = s.class_f1_mean;
    x["confusion"] = matrix(s.confusion);
    if (!s.category_macro_f1.empty()) {
      x["category_macro_f1"] = {{"mean", s.category_macro_f1_mean},
                                {"std", s.category_macro_f1_std},
                                {"runs", s.category_macro_f1}};
      x["category_confusion"] = matrix(s.category_confusion);
    }
    sources.push_back(x);
  }
  j["sources"] = sources;
  j["seconds"] = r.seconds;
  j["notes"] =
      "macro F1 std is the sample standard deviation over runs; confusion matrices are summed "
      "over runs (rows = true label, columns = predicted)";
  return j.dump(2) + "\n";
}

}  // namespace ptnet::har
