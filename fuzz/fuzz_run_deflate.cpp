// libFuzzer harness: RunDeflater (the dataset writer's level-1 deflater) on
// any bytes, its output inflated by zlib, which must give the input back.
// The first byte picks how many zero bytes are spliced between the input's
// bytes, so that both long zero runs (the pressure maps) and dense data occur.
#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "data/run_deflate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t zeros = data[0] % 64;
  std::vector<unsigned char> in;
  for (std::size_t i = 1; i < size; ++i) {
    in.push_back(data[i]);
    in.insert(in.end(), data[i] % 2 ? zeros : 0, 0);
  }
  std::vector<unsigned char> packed(ptnet::h5::RunDeflater::bound(in.size()));
  ptnet::h5::RunDeflater deflater;
  packed.resize(deflater.compress(in.data(), in.size(), packed.data()));
  std::vector<unsigned char> back(in.size() + 1);
  uLongf n = uLongf(back.size());
  if (uncompress(back.data(), &n, packed.data(), uLong(packed.size())) != Z_OK || n != in.size() ||
      !std::equal(in.begin(), in.end(), back.begin()))
    std::abort();
  return 0;
}
