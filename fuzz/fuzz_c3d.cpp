// libFuzzer harness: the C3D reader (header, parameter section, points,
// analog channels, the force plates' parameters) and, when a file reads,
// its force plates at both rates.
#include <cstdint>
#include <string_view>

#include "motion/c3d_internal.hpp"
#include "plates/plates_internal.hpp"
#include "ptnet/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const ptnet::C3d c = ptnet::parse_c3d(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.c3d");
    for (ptnet::PlateRate rate : {ptnet::PlateRate::analog, ptnet::PlateRate::markers}) {
      try {
        (void)ptnet::plates_from_c3d(c, 20, rate);
      } catch (const ptnet::Error&) {
      }
    }
  } catch (const ptnet::Error&) {
  }
  return 0;
}
