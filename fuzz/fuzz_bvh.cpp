// libFuzzer harness: the BVH parser (and the unit detection that follows a
// successful parse).
#include <cstdint>
#include <string_view>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const ptnet::Bvh bvh = ptnet::parse_bvh(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.bvh");
    (void)bvh.frames();
  } catch (const ptnet::Error&) {
  }
  return 0;
}
