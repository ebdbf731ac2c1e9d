// Digests of the weights, recorded in config.json and checked on load
// (ptnet/model.hpp).
#include <cstdio>

#include "ptnet/error.hpp"
#include "ptnet/model.hpp"

namespace ptnet {
namespace {

struct Fnv {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  void add(const std::string& s) { add(s.data(), s.size() + 1); }
};

void add_tensor(Fnv& f, const std::string& name, const torch::Tensor& t) {
  f.add(name);
  const torch::Tensor c = t.detach().to(torch::kCPU, torch::kFloat32).contiguous();
  for (const auto d : c.sizes()) f.add(&d, sizeof d);
  f.add(c.data_ptr<float>(), std::size_t(c.numel()) * sizeof(float));
}

}  // namespace

std::string weights_digest(const torch::nn::Module& net) {
  Fnv f;
  for (const auto& item : net.named_parameters(/*recurse=*/true)) add_tensor(f, item.key(), item.value());
  for (const auto& item : net.named_buffers(/*recurse=*/true)) {
    if (item.value().scalar_type() != torch::kFloat32) {  // num_batches_tracked: int64
      f.add(item.key());
      const torch::Tensor c = item.value().to(torch::kCPU).contiguous();
      f.add(c.data_ptr(), std::size_t(c.numel()) * c.element_size());
    } else {
      add_tensor(f, item.key(), item.value());
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
  return hex;
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
