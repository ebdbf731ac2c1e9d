// model/model_config_internal.hpp (private to the model stage; tests and
// the config.json fuzzer include it as "model/model_config_internal.hpp"):
// what the network's shape, its cost model and config.json's reader use
// beside ptnet/model_config.hpp. No Torch.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>

#include "ptnet/model_config.hpp"

namespace ptnet {

// Which architectures have skip connections, and which add their output to
// the input (a correction).
inline bool has_skips(Arch arch) { return arch == Arch::skip || arch == Arch::residual; }
inline bool is_residual(Arch arch) { return arch == Arch::residual || arch == Arch::frame; }

// Rows and cols after `level` poolings (level 0 = input): ceil halving.
std::array<int, 2> pooled_size(const ModelConfig& config, int level);

// Multiply-adds x 2 of one forward pass over one window (convolutions + FC).
double forward_flops(const ModelConfig& config);

// config.json's parts (src/model/config_json.cpp): a model config from its
// JSON object (`where` names it in errors), and read_model_dir on
// config.json's text (`path` names it, `dir` is the folder).
ModelConfig model_config_from_json(const nlohmann::json& j, const std::string& where);
ModelDir parse_model_config(const std::string& text, const std::string& path, const std::string& dir);

}  // namespace ptnet
