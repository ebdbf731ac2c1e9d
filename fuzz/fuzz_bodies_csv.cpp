// libFuzzer harness: the bodies CSV (and the CSV reader under it).
#include <cstdint>
#include <string>

#include "core/body_spec_internal.hpp"
#include "ptnet/body_spec.hpp"
#include "ptnet/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto bodies = ptnet::parse_bodies_csv(std::string(reinterpret_cast<const char*>(data), size), "bodies.csv");
    (void)ptnet::format_bodies_csv(bodies);
  } catch (const ptnet::Error&) {
  }
  return 0;
}
