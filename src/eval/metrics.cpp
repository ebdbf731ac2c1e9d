// Metrics of a predicted pressure sequence against ground truth (eval.hpp).
#include <cmath>
#include <utility>

#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"

namespace ptnet {

namespace {
// A NaN or infinity would make a metric NaN, or compare false everywhere
// (binary R^2 1): an Error naming the metric, the array and the index.
void check_values(const float* predicted, const float* truth, std::size_t n, const char* what) {
  for (const auto& [values, name] : {std::pair{predicted, "predicted"}, std::pair{truth, "truth"}}) {
    const std::size_t i = first_non_finite(values, n);
    if (i < n)
      throw Error(std::string(what) + ": " + name + ": non-finite value (NaN or Inf) at index " + std::to_string(i));
  }
}
}  // namespace

namespace {
// A binarisation threshold: NaN would compare false everywhere (every cell
// "no contact", R^2 1) and a negative one marks every cell as contact.
void check_threshold(double threshold_kpa, const char* what) {
  if (!kThresholdKpaRange.contains(threshold_kpa))
    throw Error(std::string(what) + ": threshold_kpa: expected a finite number >= 0, found " +
                number_text(threshold_kpa));
}

// The metrics on checked values (compare checks its arrays once for all three).
double rmse_of(const float* predicted, const float* truth, std::size_t n) {
  if (n == 0) return 0;
  double sse = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = double(predicted[i]) - double(truth[i]);
    sse += d * d;
  }
  return std::sqrt(sse / double(n));
}

double binary_r2_of(const float* predicted, const float* truth, std::size_t n, double threshold_kpa) {
  std::size_t ones = 0, mismatches = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool t = truth[i] > threshold_kpa, p = predicted[i] > threshold_kpa;
    ones += t;
    mismatches += (t != p);
  }
  return binary_r2_from_counts(double(mismatches), double(ones), double(n));
}

double contact_iou_of(const float* predicted, const float* truth, std::size_t n, double threshold_kpa) {
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool t = truth[i] > threshold_kpa, p = predicted[i] > threshold_kpa;
    both += (t && p);
    either += (t || p);
  }
  return either == 0 ? 1.0 : double(both) / double(either);
}
}  // namespace

double rmse(const float* predicted, const float* truth, std::size_t n) {
  check_values(predicted, truth, n, "rmse");
  return rmse_of(predicted, truth, n);
}

double binary_r2(const float* predicted, const float* truth, std::size_t n, double threshold_kpa) {
  check_threshold(threshold_kpa, "binary_r2");
  check_values(predicted, truth, n, "binary_r2");
  return binary_r2_of(predicted, truth, n, threshold_kpa);
}

double contact_iou(const float* predicted, const float* truth, std::size_t n, double threshold_kpa) {
  check_threshold(threshold_kpa, "contact_iou");
  check_values(predicted, truth, n, "contact_iou");
  return contact_iou_of(predicted, truth, n, threshold_kpa);
}

SequenceMetrics compare(const PressureSequence& predicted, const PressureSequence& truth,
                        const MetricOptions& options) {
  for (const PressureSequence* s : {&predicted, &truth})
    if (!(s->mat.pitch_m > 0) || !std::isfinite(s->mat.pitch_m))  // the centre of pressure's cm
      throw Error("compare: pitch_m: expected a cell size > 0 m, found " + number_text(s->mat.pitch_m));
  if (predicted.mat.pitch_m != truth.mat.pitch_m)
    throw Error("compare: mats differ in pitch_m (" + number_text(predicted.mat.pitch_m) + " vs " +
                number_text(truth.mat.pitch_m) + " m)");
  if (!(predicted.mat == truth.mat) || predicted.frames() != truth.frames())
    throw Error("compare: shapes differ (" + std::to_string(predicted.frames()) + " x " +
                std::to_string(predicted.mat.rows) + " x " + std::to_string(predicted.mat.cols) +
                " vs " + std::to_string(truth.frames()) + " x " +
                std::to_string(truth.mat.rows) + " x " + std::to_string(truth.mat.cols) + ")");
  const std::size_t n = truth.kpa.size();
  SequenceMetrics m;
  check_threshold(options.threshold_kpa, "binary_r2");
  check_values(predicted.kpa.data(), truth.kpa.data(), n, "compare");
  m.rmse_kpa = rmse_of(predicted.kpa.data(), truth.kpa.data(), n);
  m.binary_r2 = binary_r2_of(predicted.kpa.data(), truth.kpa.data(), n, options.threshold_kpa);
  m.contact_iou = contact_iou_of(predicted.kpa.data(), truth.kpa.data(), n, options.threshold_kpa);

  double force_p = 0, force_t = 0, cop_sum_m = 0;
  for (int t = 0; t < truth.frames(); ++t) {
    const FrameLoad p = frame_load(predicted.frame(t), truth.mat), q = frame_load(truth.frame(t), truth.mat);
    force_p += p.force_n;
    force_t += q.force_n;
    if (p.force_n > 0 && q.force_n > 0) {
      cop_sum_m += std::hypot(p.x_m - q.x_m, p.y_m - q.y_m);
      ++m.cop_frames;
    }
  }
  m.cop_error_cm = m.cop_frames ? cop_sum_m / m.cop_frames * 100.0 : 0.0;
  if (force_t > 0)
    m.force_error_pct = std::abs(force_p - force_t) / force_t * 100.0;
  else
    m.force_error_pct = force_p > 0 ? 100.0 : 0.0;
  return m;
}

PressureSequence copy_baseline(const PressureSequence& source) { return source; }

PressureSequence weight_ratio_baseline(const PressureSequence& source, double source_weight_kg,
                                       double target_weight_kg) {
  if (!(source_weight_kg > 0) || !(target_weight_kg > 0))
    throw Error("weight_ratio_baseline: weights must be positive");
  PressureSequence out = source;
  const float ratio = float(target_weight_kg / source_weight_kg);
  for (float& v : out.kpa) v *= ratio;
  return out;
}

PressureSequence body_scale_baseline(const PressureSequence& source, const BodySpec& source_body,
                                     const BodySpec& target_body) {
  return zoom_about_centre(source, body_scale(source_body.height_cm, target_body.height_cm),
                           body_gain(source_body.height_cm, source_body.weight_kg, target_body.height_cm,
                                     target_body.weight_kg));
}

}  // namespace ptnet
