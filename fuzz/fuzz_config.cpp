// libFuzzer harness: a model folder's config.json.
#include <cstdint>
#include <string>

#include "model/model_config_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const ptnet::ModelDir d =
        ptnet::parse_model_config(std::string(reinterpret_cast<const char*>(data), size), "config.json", ".");
    (void)ptnet::parameter_count(d.model);
    (void)ptnet::recorded_digest(d, "checkpoint.pt");
  } catch (const ptnet::Error&) {
  }
  return 0;
}
