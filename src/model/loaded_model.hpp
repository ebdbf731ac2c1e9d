// A model folder loaded for inference (Transfer, Stream): config.json and
// model.pt validated, the module in eval mode and its InferenceNet.
// Internal to the model stage (includes Torch).
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "ptnet/model.hpp"

namespace ptnet {

struct LoadedModel {
  ModelDir dir;
  torch::Device device = torch::kCPU;
  PressureTransferNet net{nullptr};     // the reference (and the CUDA path)
  std::unique_ptr<InferenceNet> fast;   // CPU: BatchNorm and FiLM folded
  std::mutex mutex;                     // fast's per-pair cache: one forward at a time

  // x [N, T, H, W], source, target [N, A] (on the CPU) -> [N, T, H, W] >= 0 on the CPU.
  torch::Tensor forward(const torch::Tensor& x, const torch::Tensor& source, const torch::Tensor& target);
};

// Throws Error naming the file (missing folder, bad config.json, weights that
// do not match) or the option (threads out of range, no CUDA). `batch` is the
// windows per forward pass, for the memory check. threads > 0 sets Torch's
// intra-op threads.
std::unique_ptr<LoadedModel> load_model(const std::string& model_dir, const std::string& device, int threads,
                                        int batch);

}  // namespace ptnet
