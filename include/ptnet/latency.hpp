// ptnet/latency.hpp: the median, 99th percentile and maximum of any number
// of durations in a fixed footprint (a live stream's per-frame latency).
//
//   ptnet::LatencySummary s;
//   s.add(1.73);                        // one frame's latency, ms
//   s.quantile(0.99);                   // within 1 % of the exact order statistic
//
// Durations are counted in logarithmic bins 2 % wide from 1 us to 100 s
// (930 counters, 7.4 KB whatever the count); a quantile is the middle of
// its bin, so within 1 % of the duration of that rank (clamped to the
// smallest and largest seen, which are exact, as are q = 0 and 1).
// Durations outside the range fall in the end bins.
#pragma once

#include <array>
#include <cstdint>

namespace ptnet {

class LatencySummary {
 public:
  void add(double ms);
  std::int64_t count() const { return count_; }
  double max() const { return max_; }  // 0 when empty
  // The duration of rank round(q (count - 1)) in increasing order, q in
  // [0, 1]; 0 when empty.
  double quantile(double q) const;

  static constexpr double kSmallestMs = 1e-3;  // 1 us
  static constexpr double kBinRatio = 1.02;    // bin width: 2 %
  static constexpr int kBins = 930;            // up to 1e-3 x 1.02^930 ms = 100 s

 private:
  std::array<std::int64_t, kBins> bins_{};
  std::int64_t count_ = 0;
  double min_ = 0, max_ = 0;
};

}  // namespace ptnet
