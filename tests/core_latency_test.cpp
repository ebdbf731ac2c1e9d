// LatencySummary: quantiles within 1 % of the exact order statistics, the
// count and maximum exact, in a footprint that does not grow with the count
// (a stream may run for days).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <type_traits>
#include <vector>

#include "ptnet/latency.hpp"

using ptnet::LatencySummary;

TEST(LatencySummary, QuantilesWithinTheBinWidth) {
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> ms(0.5, 0.8);  // a latency-like spread: ~0.3 to ~20 ms
  LatencySummary s;
  std::vector<double> all;
  for (int i = 0; i < 200000; ++i) {
    const double v = ms(rng);
    s.add(v);
    all.push_back(v);
  }
  std::sort(all.begin(), all.end());
  const auto exact = [&](double q) { return all[std::size_t(q * double(all.size() - 1) + 0.5)]; };
  EXPECT_EQ(s.count(), std::int64_t(all.size()));
  EXPECT_EQ(s.max(), all.back());
  for (double q : {0.0, 0.01, 0.5, 0.9, 0.99, 0.999, 1.0})
    EXPECT_NEAR(s.quantile(q), exact(q), 0.01 * exact(q)) << "q " << q;  // half a 2 % bin
}

TEST(LatencySummary, FixedFootprintAndEdges) {
  // No heap: the summary is its fixed array of counters, whatever it counts.
  static_assert(std::is_trivially_copyable_v<LatencySummary>);
  static_assert(sizeof(LatencySummary) < 8 * 1024);
  LatencySummary s;
  EXPECT_EQ(s.quantile(0.5), 0.0);
  for (int i = 0; i < 1000; ++i) s.add(1e-6);  // below the range
  s.add(1e7);                                   // above it
  s.add(-1);                                    // a clock step back: 0
  EXPECT_EQ(s.count(), 1002);
  EXPECT_EQ(s.max(), 1e7);
  EXPECT_LE(s.quantile(0.5), LatencySummary::kSmallestMs * LatencySummary::kBinRatio);
  EXPECT_EQ(s.quantile(1.0), 1e7);  // clamped to the largest seen
}
