// Classification metrics (ptnet/har.hpp): confusion matrix, per-class
// precision / recall / F1, macro F1 as scikit-learn computes it with
// labels=None and zero_division=0, accuracy.
#include <algorithm>
#include <cmath>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

// Sample standard deviation (n - 1).
double sd_of(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size() - 1));
}

std::vector<int> argmax_rows(const std::vector<float>& scores, int columns) {
  if (columns < 1 || scores.size() % std::size_t(columns) != 0)
    throw Error("metrics: " + std::to_string(scores.size()) + " scores are not rows of " + std::to_string(columns));
  std::vector<int> out(scores.size() / std::size_t(columns));
  for (std::size_t r = 0; r < out.size(); ++r) {
    const float* row = scores.data() + r * std::size_t(columns);
    out[r] = int(std::max_element(row, row + columns) - row);
  }
  return out;
}

ClassificationReport classification_report(const std::vector<int>& truth,
                                            const std::vector<int>& predicted, int classes) {
  if (truth.size() != predicted.size())
    throw Error("metrics: " + std::to_string(truth.size()) + " true labels but " +
                std::to_string(predicted.size()) + " predictions");
  if (truth.empty()) throw Error("metrics: no labels to score");
  if (classes < 1) throw Error("metrics: need at least one class, found " + std::to_string(classes));
  ClassificationReport r;
  r.classes = classes;
  r.confusion = Eigen::MatrixXi::Zero(classes, classes);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const int t = truth[i], p = predicted[i];
    if (t < 0 || t >= classes || p < 0 || p >= classes)
      throw Error("metrics: label " + std::to_string(t < 0 || t >= classes ? t : p) +
                  " outside 0.." + std::to_string(classes - 1));
    ++r.confusion(t, p);
  }
  r.precision.assign(classes, 0.0);
  r.recall.assign(classes, 0.0);
  r.f1.assign(classes, 0.0);
  r.support.assign(classes, 0);
  r.present.assign(classes, false);
  double sum = 0;
  int present = 0;
  long long correct = 0;
  for (int c = 0; c < classes; ++c) {
    const long long tp = r.confusion(c, c);
    const long long actual = r.confusion.row(c).sum();
    const long long guessed = r.confusion.col(c).sum();
    correct += tp;
    r.support[c] = int(actual);
    r.present[c] = actual > 0 || guessed > 0;
    if (guessed > 0) r.precision[c] = double(tp) / double(guessed);
    if (actual > 0) r.recall[c] = double(tp) / double(actual);
    if (actual + guessed > 0) r.f1[c] = 2.0 * double(tp) / double(actual + guessed);
    if (r.present[c]) {
      sum += r.f1[c];
      ++present;
    }
  }
  r.macro_f1 = present ? sum / present : 0.0;
  r.accuracy = double(correct) / double(truth.size());
  return r;
}

}  // namespace ptnet::har
