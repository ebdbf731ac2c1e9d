// Core's shared helpers that several stages once kept their own copies of:
// FNV-1a 64 (digests and name-derived seeds), the binary R^2 from counts and
// a frame's load (force, centre of pressure, contact area), the line reader
// of every text format, the range check of pressure readings.
// The values are pinned: they decide simulated sensor noise, recorded
// digests and the validation split, so a change would change outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/hash.hpp"
#include "ptnet/error.hpp"
#include "ptnet/pressure.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/strings.hpp"

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

// A frame read as a force plate: the force is pressure x area (kPa x 1000 x
// pitch^2 per cell), the centre of pressure is the pressure-weighted centre
// in the mat's frame (x towards row 0, y towards column 0), negative cells
// carry nothing, and an empty frame has no centre.
TEST(CoreFrameLoad, ForceCentreAndAreaOfKnownFrames) {
  const MatSpec mat;  // 80 x 28, 2 cm
  std::vector<float> f(std::size_t(mat.cells()), 0.0f);
  const FrameLoad empty = frame_load(f.data(), mat);
  EXPECT_EQ(empty.force_n, 0.0);
  EXPECT_TRUE(std::isnan(empty.x_m) && std::isnan(empty.y_m));
  // 100 kPa on cell (0, 0), the far left corner; 300 kPa on cell (79, 27).
  f[0] = 100.0f;
  f[std::size_t(79 * 28 + 27)] = 300.0f;
  f[5] = -50.0f;  // below zero: no load
  const FrameLoad l = frame_load(f.data(), mat);
  EXPECT_NEAR(l.force_n, 400 * 1000 * 0.02 * 0.02, 1e-9);  // 160 N
  // Cell centres at x = 0.8 - 0.01 = 0.79 and -0.79, y = 0.28 - 0.01 = 0.27 and -0.27.
  EXPECT_NEAR(l.x_m, (100 * 0.79 + 300 * -0.79) / 400, 1e-12);
  EXPECT_NEAR(l.y_m, (100 * 0.27 + 300 * -0.27) / 400, 1e-12);
  EXPECT_NEAR(l.contact_m2, 2 * 0.0004, 1e-15);
  EXPECT_NEAR(frame_load(f.data(), mat, 150).contact_m2, 0.0004, 1e-15);  // only the 300 kPa cell
}

TEST(CorePressureCheck, EveryValueOutOfRangeIsFoundWherever) {
  // Four at a time and the tail one by one: a bad value at every position
  // of arrays of 1-13 values is refused, naming its frame; good ones pass.
  const float bad[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                       -std::numeric_limits<float>::infinity(), -0.5f, 2e6f};
  for (std::size_t n = 1; n <= 13; ++n) {
    std::vector<float> v(n, 3.5f);
    v[0] = -0.0f, v[n - 1] = float(kPressureRangeKpa.hi);
    EXPECT_NO_THROW(check_pressure(v.data(), n, 2, "f", "x")) << n;
    for (std::size_t k = 0; k < n; ++k)
      for (float b : bad) {
        std::vector<float> w = v;
        w[k] = b;
        try {
          check_pressure(w.data(), n, 2, "f", "x");
          ADD_FAILURE() << b << " at " << k << " of " << n << " passed";
        } catch (const Error& e) {
          EXPECT_NE(e.message().find("frame " + std::to_string(k / 2)), std::string::npos) << e.message();
        }
      }
  }
}

}  // namespace
}  // namespace ptnet

TEST(CoreLineReader, ByteOrderMarkCrlfAndLineNumbers) {
  const std::string text = "\xEF\xBB\xBF" "a\tb\r\n\r\nlast";
  ptnet::LineReader lines(text);
  EXPECT_EQ(lines.lines_left(), 3u);
  std::vector<std::pair<std::string, long>> got;
  for (std::string_view l; lines.next(l);) got.emplace_back(std::string(l), lines.number());
  EXPECT_EQ(got, (std::vector<std::pair<std::string, long>>{{"a\tb", 1}, {"", 2}, {"last", 3}}));
  EXPECT_EQ(lines.lines_left(), 0u);
  // A final LF ends the last line; it starts none.
  ptnet::LineReader two("x\ny\n");
  EXPECT_EQ(two.lines_left(), 2u);
  std::string_view l;
  int n = 0;
  while (two.next(l)) ++n;
  EXPECT_EQ(n, 2);
}

TEST(CoreStrings, ViewsSplitAndTrimAsTheCopiesDo) {
  std::vector<std::string_view> v;
  ptnet::split_views(" a \t, b,,c ", ',', v);
  EXPECT_EQ(std::vector<std::string>(v.begin(), v.end()), ptnet::split(" a \t, b,,c ", ','));
  EXPECT_EQ(std::vector<std::string>(v.begin(), v.end()), (std::vector<std::string>{"a", "b", "", "c"}));
  ptnet::split_blanks("  x\t\ty  z ", v);
  EXPECT_EQ(std::vector<std::string>(v.begin(), v.end()), ptnet::split_blanks("  x\t\ty  z "));
  EXPECT_EQ(v.size(), 3u);
  EXPECT_EQ(ptnet::trim_view(" \tq r\r\n"), "q r");
}
