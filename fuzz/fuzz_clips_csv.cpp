// libFuzzer harness: the clips CSV (rows naming files that do not exist end
// at the existence check, after every other field is validated).
#include <cstdint>
#include <string>

#include "data/data_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/simulate_dataset.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)ptnet::parse_clips_csv(std::string(reinterpret_cast<const char*>(data), size), "/nonexistent/clips.csv");
  } catch (const ptnet::Error&) {
  }
  return 0;
}
