// libFuzzer harness: the archive check run on model.pt and checkpoint.pt.
#include <cstdint>
#include <string_view>

#include "core/zip_check.hpp"
#include "ptnet/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)ptnet::verify_zip(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.pt");
  } catch (const ptnet::Error&) {
  }
  return 0;
}
