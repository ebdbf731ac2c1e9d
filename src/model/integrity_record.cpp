// The weights' digests as config.json's "integrity" records them
// (ptnet/model_config.hpp); the digests themselves: integrity.cpp. No Torch
// here (the config.json fuzzer compiles it).
#include <string>

#include "ptnet/model_config.hpp"

namespace ptnet {
using nlohmann::json;

std::string recorded_digest(const ModelDir& dir, const std::string& file, int* epoch) {
  if (epoch) *epoch = -1;
  if (!dir.integrity.is_object() || !dir.integrity.contains(file)) return "";
  const json& v = dir.integrity.at(file);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_object() && v.contains("digest") && v["digest"].is_string()) {
    if (epoch && v.contains("epoch") && v["epoch"].is_number_integer()) *epoch = v["epoch"].get<int>();
    return v["digest"].get<std::string>();
  }
  return "";
}

void record_digest(ModelDir& dir, const std::string& file, const std::string& digest, int epoch) {
  if (!dir.integrity.is_object()) dir.integrity = json::object();
  dir.integrity[file] = epoch >= 0 ? json{{"epoch", epoch}, {"digest", digest}} : json(digest);
}

}  // namespace ptnet
