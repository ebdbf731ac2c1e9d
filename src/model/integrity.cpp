// Digests of the weights (ptnet/model.hpp), recorded in config.json's
// "integrity" (integrity_record.cpp) and checked on load.
#include "core/hash.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model.hpp"

namespace ptnet {
namespace {

// A name with its terminating NUL, so that names and data cannot run together.
void add_name(Fnv1a& f, const std::string& name) { f.add(name).add_byte(0); }

void add_tensor(Fnv1a& f, const std::string& name, const torch::Tensor& t) {
  add_name(f, name);
  const torch::Tensor c = t.detach().to(torch::kCPU, torch::kFloat32).contiguous();
  for (const auto d : c.sizes()) f.add(&d, sizeof d);
  f.add(c.data_ptr<float>(), std::size_t(c.numel()) * sizeof(float));
}

}  // namespace

std::string weights_digest(const torch::nn::Module& net) {
  Fnv1a f;
  for (const auto& item : net.named_parameters(/*recurse=*/true)) add_tensor(f, item.key(), item.value());
  for (const auto& item : net.named_buffers(/*recurse=*/true)) {
    if (item.value().scalar_type() != torch::kFloat32) {  // num_batches_tracked: int64
      add_name(f, item.key());
      const torch::Tensor c = item.value().to(torch::kCPU).contiguous();
      f.add(c.data_ptr(), std::size_t(c.numel()) * c.element_size());
    } else {
      add_tensor(f, item.key(), item.value());
    }
  }
  return f.hex();
}

void check_weights_digest(const torch::nn::Module& net, const std::string& recorded, const std::string& path,
                          const std::string& config_path) {
  if (recorded.empty()) return;
  const std::string found = weights_digest(net);
  if (found != recorded)
    throw Error::in(path, "weights do not match the digest in " + config_path + " (" + found + ", recorded " +
                              recorded + "): corrupt or replaced file");
}

}  // namespace ptnet
