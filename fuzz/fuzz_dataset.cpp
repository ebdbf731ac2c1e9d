// libFuzzer harness: the dataset reader on an in-memory HDF5 file image
// (core driver): structure, bodies, sequence attributes, then the frames of
// every sequence small enough to read.
#include <cstdint>
#include <string>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "support/dataset_image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const ptnet::Dataset d = ptnet::open_dataset_image(std::string(reinterpret_cast<const char*>(data), size),
                                                       "fuzz.h5");
    for (const auto& m : d.sequences())
      if (std::uint64_t(m.frames) * std::uint64_t(d.info().mat.cells()) <= (1u << 20)) (void)d.read(m.name);
  } catch (const ptnet::Error&) {
  }
  return 0;
}
