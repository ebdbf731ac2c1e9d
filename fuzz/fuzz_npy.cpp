// libFuzzer harness: the .npy reader, then the [T, rows, cols] sequence view.
#include <cstdint>
#include <string>

#include "core/npy_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/npy.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const ptnet::NpyArray a = ptnet::parse_npy(std::string(reinterpret_cast<const char*>(data), size), "fuzz.npy");
    (void)a.data.size();
  } catch (const ptnet::Error&) {
  }
  return 0;
}
