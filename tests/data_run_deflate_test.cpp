// RunDeflater (src/data/run_deflate.hpp): its zlib streams inflate, with
// zlib's own inflater (the one HDF5's deflate filter calls), to the exact
// input, whatever the input: empty, incompressible, all zeros, sparse, and
// skewed enough that the Huffman codes need their 15-bit limit; and its
// bytes are pinned (the datasets' bytes are: a faster coder must write the
// same stream).
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "core/hash.hpp"
#include "data/run_deflate.hpp"

namespace ptnet::h5 {
namespace {

// Compresses and inflates `in`; returns the compressed size.
std::size_t round_trip(RunDeflater& d, const std::vector<unsigned char>& in) {
  std::vector<unsigned char> z(RunDeflater::bound(in.size())), back(in.size() + 1);
  const std::size_t n = d.compress(in.data(), in.size(), z.data());
  EXPECT_LE(n, z.size());
  uLongf got = uLongf(back.size());
  EXPECT_EQ(uncompress(back.data(), &got, z.data(), uLong(n)), Z_OK) << in.size() << " bytes";
  EXPECT_EQ(got, in.size());
  EXPECT_EQ(std::memcmp(back.data(), in.data(), std::min<std::size_t>(got, in.size())), 0) << in.size() << " bytes";
  return n;
}

TEST(RunDeflate, InflatesToTheInputWhateverTheInput) {
  RunDeflater d;  // reused, as the writer does
  std::mt19937 rng(5);
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<unsigned char> in(rng() % (trial < 40 ? 10 : 40000));
    const int kind = trial % 5;
    for (std::size_t i = 0; i < in.size(); ++i) {
      const unsigned r = rng();
      in[i] = kind == 0   ? static_cast<unsigned char>(r)               // incompressible
              : kind == 1 ? (r % 100 < 97 ? 0 : static_cast<unsigned char>(r))  // sparse
              : kind == 2 ? 0                                              // all zeros
              : kind == 3 ? static_cast<unsigned char>(r % 3)              // short runs of zeros
                          : ((i / 300) % 2 ? 0 : static_cast<unsigned char>(r));  // long runs
    }
    round_trip(d, in);
  }
}

TEST(RunDeflate, LimitsCodeLengthsOnSkewedInput) {
  // Fibonacci symbol counts: an unlimited Huffman code would be 24 bits deep.
  std::vector<unsigned char> in;
  for (unsigned s = 0, a = 1, b = 1; s < 25; ++s, std::swap(a, b), b += a)
    in.insert(in.end(), a, static_cast<unsigned char>(s + 1));
  std::shuffle(in.begin(), in.end(), std::mt19937(3));
  RunDeflater d;
  round_trip(d, in);
}

TEST(RunDeflate, SparseFramesCompressWell) {
  std::vector<float> frames(32 * 80 * 28, 0.0f);  // one chunk, a few pressed cells per frame
  for (int t = 0; t < 32; ++t)
    for (int c = 0; c < 30; ++c) frames[std::size_t(t * 2240 + 900 + c * 3)] = 0.1f * float(t + c + 1);
  std::vector<unsigned char> in(frames.size() * 4);
  std::memcpy(in.data(), frames.data(), in.size());
  RunDeflater d;
  EXPECT_LT(round_trip(d, in) * 50, in.size());
}

TEST(RunDeflate, StreamsArePinned) {
  // Every kind of input of the first test, and sparse frames with long runs
  // of zeros between pressed cells: the digest of all their streams.
  RunDeflater d;
  std::mt19937 rng(11);
  Fnv1a digest;
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<unsigned char> in(rng() % 300000);
    const int kind = trial % 6;
    for (std::size_t i = 0; i < in.size(); ++i) {
      const unsigned r = rng();
      in[i] = kind == 0   ? static_cast<unsigned char>(r)
              : kind == 1 ? (r % 100 < 97 ? 0 : static_cast<unsigned char>(r))
              : kind == 2 ? 0
              : kind == 3 ? static_cast<unsigned char>(r % 3)
              : kind == 4 ? ((i / 300) % 2 ? 0 : static_cast<unsigned char>(r))
                          : (r % 4000 < 3 ? static_cast<unsigned char>(r >> 12) : 0);
    }
    std::vector<unsigned char> z(RunDeflater::bound(in.size()));
    const std::size_t n = d.compress(in.data(), in.size(), z.data());
    digest.add(z.data(), n).add_byte(0);
  }
  EXPECT_EQ(digest.hex(), "a8bdd51cbc860240");
}

}  // namespace
}  // namespace ptnet::h5
