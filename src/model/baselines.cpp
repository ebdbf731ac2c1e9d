// Naive transfer baselines and RMSE (no Torch).
#include "ptnet/baselines.hpp"

#include <cmath>
#include <string>

#include "ptnet/error.hpp"

namespace ptnet {

PressureSequence baseline_copy(const PressureSequence& src) { return src; }

PressureSequence baseline_weight_scale(const PressureSequence& src, const BodySpec& source,
                                       const BodySpec& target) {
  if (!(source.weight_kg > 0) || !(target.weight_kg > 0))
    throw Error("baseline_weight_scale: weights must be > 0 kg");
  PressureSequence out = src;
  const float ratio = float(target.weight_kg / source.weight_kg);
  for (float& v : out.kpa) v *= ratio;
  return out;
}

double rmse_kpa(const PressureSequence& a, const PressureSequence& b) {
  if (!(a.mat.rows == b.mat.rows && a.mat.cols == b.mat.cols))
    throw Error("rmse: mats differ (" + std::to_string(a.mat.rows) + "x" + std::to_string(a.mat.cols) +
                " vs " + std::to_string(b.mat.rows) + "x" + std::to_string(b.mat.cols) + ")");
  if (a.kpa.size() != b.kpa.size())
    throw Error("rmse: frame counts differ (" + std::to_string(a.frames()) + " vs " +
                std::to_string(b.frames()) + ")");
  if (a.kpa.empty()) throw Error("rmse: empty sequences");
  double sum = 0;
  for (std::size_t i = 0; i < a.kpa.size(); ++i) {
    const double d = double(a.kpa[i]) - double(b.kpa[i]);
    sum += d * d;
  }
  return std::sqrt(sum / double(a.kpa.size()));
}

}  // namespace ptnet
