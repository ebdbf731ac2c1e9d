// Core's shared helpers that several stages once kept their own copies of:
// FNV-1a 64 (digests and name-derived seeds) and the binary R^2 from counts.
// The values are pinned: they decide simulated sensor noise, recorded
// digests and the validation split, so a change would change outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/hash.hpp"
#include "ptnet/pressure.hpp"
#include "ptnet/sim.hpp"

namespace ptnet {
namespace {

TEST(CoreHash, Fnv1aTestVectors) {
  EXPECT_EQ(fnv1a(""), 0xcbf29ce484222325ull);  // the offset basis
  EXPECT_EQ(fnv1a("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(Fnv1a().add("foobar").hex(), "85944171f73967e8");
  EXPECT_EQ(Fnv1a().hex(), "cbf29ce484222325");
}

TEST(CoreHash, PiecesHashLikeTheirConcatenation) {
  const std::string bytes("name\0\xff" "data", 10);
  EXPECT_EQ(Fnv1a().add("name").add_byte(0).add_byte(0xff).add("data", 4).value(), fnv1a(bytes));
}

TEST(CoreHash, TheTruncatedBasisKeepsRecordedValues) {
  EXPECT_EQ(fnv1a("", Fnv1a::kTruncatedBasis), 0x14650fb0739d0383ull);
  EXPECT_EQ(fnv1a("walk_01", Fnv1a::kTruncatedBasis), 0x7d922257ee9c6908ull);
}

TEST(CoreHash, SequenceSeedsAreUnchanged) {
  // Values of the sequence seed as simulate wrote them before the hash moved
  // to core (FNV-1a of the name, then a splitmix64 finaliser).
  EXPECT_EQ(sequence_seed(7, "walk__b2"), 13293596661775560013ull);
  EXPECT_EQ(sequence_seed(0, "001_01__b1"), 13643914538663015982ull);
}

TEST(CoreBinaryR2, FromCounts) {
  // q = 0.25: SS_tot = 100 * 0.25 * 0.75 = 18.75.
  EXPECT_DOUBLE_EQ(binary_r2_from_counts(0, 25, 100), 1.0);
  EXPECT_DOUBLE_EQ(binary_r2_from_counts(3, 25, 100), 1.0 - 3 / 18.75);
  EXPECT_DOUBLE_EQ(binary_r2_from_counts(37.5, 25, 100), -1.0);  // worse than the mean: negative
}

TEST(CoreBinaryR2, ConstantOrEmptyTruthIsNeverNan) {
  EXPECT_EQ(binary_r2_from_counts(0, 0, 10), 1.0);
  EXPECT_EQ(binary_r2_from_counts(2, 0, 10), 0.0);
  EXPECT_EQ(binary_r2_from_counts(0, 10, 10), 1.0);
  EXPECT_EQ(binary_r2_from_counts(1, 10, 10), 0.0);
  EXPECT_EQ(binary_r2_from_counts(0, 0, 0), 1.0);
}

}  // namespace
}  // namespace ptnet
