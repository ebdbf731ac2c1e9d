// Durations in logarithmic bins (ptnet/latency.hpp).
#include "ptnet/latency.hpp"

#include <algorithm>
#include <cmath>

namespace ptnet {

void LatencySummary::add(double ms) {
  if (!(ms >= 0)) ms = 0;  // NaN or a clock step back
  const double bin = ms > kSmallestMs ? std::floor(std::log(ms / kSmallestMs) / std::log(kBinRatio)) : 0;
  ++bins_[std::size_t(std::min(bin, double(kBins - 1)))];
  min_ = count_ == 0 ? ms : std::min(min_, ms);
  max_ = count_ == 0 ? ms : std::max(max_, ms);
  ++count_;
}

double LatencySummary::quantile(double q) const {
  if (count_ == 0) return 0;
  const auto rank = std::int64_t(std::clamp(q, 0.0, 1.0) * double(count_ - 1) + 0.5);
  if (rank == 0) return min_;  // the ends are exact
  if (rank == count_ - 1) return max_;
  std::int64_t below = 0;
  int bin = 0;
  for (; bin < kBins - 1 && below + bins_[std::size_t(bin)] <= rank; ++bin) below += bins_[std::size_t(bin)];
  const double middle = kSmallestMs * std::pow(kBinRatio, bin + 0.5);
  return std::clamp(middle, min_, max_);
}

}  // namespace ptnet
