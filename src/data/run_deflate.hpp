// run_deflate.hpp (internal to the data stage): a zlib-format (RFC 1950 /
// RFC 1951) compressor for data that is mostly runs of zero bytes, such as
// pressure frames where ~98 % of the cells read 0. It finds only runs of
// zeros (coded as distance-1 matches, as zlib's Z_RLE strategy does) and
// codes them and the other bytes as literals in one dynamic Huffman block.
// Runs are found 8 bytes at a time, so it is several times faster than a
// general match finder, at a ratio as good on such data. Any inflater (zlib,
// HDF5's deflate filter, h5py) decodes its output.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace ptnet::h5 {

class RunDeflater {
 public:
  // Worst-case output size for n input bytes.
  static std::size_t bound(std::size_t n) { return 2 * n + 1024; }
  // Compresses in[0, n) into out (at least bound(n) bytes) as one zlib
  // stream; returns its size.
  std::size_t compress(const unsigned char* in, std::size_t n, unsigned char* out);

 private:
  std::vector<std::uint16_t> tokens_;  // byte 0-255, or 256 + match length (3-258) at distance 1
};

}  // namespace ptnet::h5
