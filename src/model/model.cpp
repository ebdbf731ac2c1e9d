// PressureTransferNet module, weights I/O. The only Torch translation unit of
// the model stage besides transfer.cpp.
//
// Dimension legend: N windows, T frames (channels), H x W mat cells,
// A = 3 attributes, C1..C3 conv widths.
#include "ptnet/model.hpp"

#include <filesystem>
#include <sstream>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/zip_check.hpp"

namespace ptnet {
namespace nn = torch::nn;

namespace {

nn::Conv2dOptions conv_options(int in, int out) { return nn::Conv2dOptions(in, out, 3).padding(1); }
nn::ConvTranspose2dOptions deconv_options(int in, int out) {
  return nn::ConvTranspose2dOptions(in, out, 3).padding(1);
}
int skip_factor(const ModelConfig& c) { return has_skips(c.arch) ? 2 : 1; }
// (MaxUnpool2d of LibTorch 1.13 rejects a 2-element output_size, hence the
// functional torch::max_unpool2d in forward().)
std::int64_t flat_size(const ModelConfig& c) {
  auto s = pooled_size(c, kPoolLevels);
  return std::int64_t(c.channels[2]) * s[0] * s[1];
}
const ModelConfig& checked(const ModelConfig& c) {
  validate(c);
  return c;
}

}  // namespace

PressureTransferNetImpl::PressureTransferNetImpl(const ModelConfig& config)
    : config_(checked(config)),
      conv1(conv_options(config.window, config.channels[0])),
      conv2(conv_options(config.channels[0], config.channels[1])),
      conv3(conv_options(config.channels[1], config.channels[2])),
      bn1(config.channels[0]),
      bn2(config.channels[1]),
      bn3(config.channels[2]),
      pool(nn::MaxPool2dOptions(2).stride(2).ceil_mode(true)),
      fc_features(flat_size(config), config.hidden),
      fc_latent(config.hidden + kAttributes, config.latent),
      fc_decode(config.latent + kAttributes, flat_size(config)),
      deconv3(deconv_options(config.channels[2] * skip_factor(config), config.channels[1])),
      deconv2(deconv_options(config.channels[1] * skip_factor(config), config.channels[0])),
      deconv1(deconv_options(config.channels[0] * skip_factor(config), config.window)),
      dbn3(config.channels[1]),
      dbn2(config.channels[0]) {
  register_module("conv1", conv1);
  register_module("conv2", conv2);
  register_module("conv3", conv3);
  register_module("bn1", bn1);
  register_module("bn2", bn2);
  register_module("bn3", bn3);
  register_module("pool", pool);
  register_module("fc_features", fc_features);
  register_module("fc_latent", fc_latent);
  register_module("fc_decode", fc_decode);
  register_module("deconv3", deconv3);
  register_module("deconv2", deconv2);
  register_module("deconv1", deconv1);
  register_module("dbn3", dbn3);
  register_module("dbn2", dbn2);
  if (config.arch == Arch::residual) {
    // Zero-initialised correction: an untrained residual model is exactly its
    // (aligned) input, and training starts from that baseline.
    torch::NoGradGuard no_grad;
    deconv1->weight.zero_();
    deconv1->bias.zero_();
  }
}

torch::Tensor PressureTransferNetImpl::forward(const torch::Tensor& x, const torch::Tensor& source,
                                               const torch::Tensor& target) {
  return torch::relu(forward_raw(x, source, target));  // [N,T,H,W] >= 0
}

torch::Tensor PressureTransferNetImpl::forward_raw(const torch::Tensor& x, const torch::Tensor& source,
                                                   const torch::Tensor& target) {
  const auto& c = config_;
  TORCH_CHECK(x.dim() == 4 && x.size(1) == c.window && x.size(2) == c.rows && x.size(3) == c.cols,
              "PressureTransferNet: expected input [N, ", c.window, ", ", c.rows, ", ", c.cols,
              "], found ", x.sizes());
  TORCH_CHECK(source.dim() == 2 && source.size(1) == kAttributes && target.sizes() == source.sizes() &&
                  source.size(0) == x.size(0),
              "PressureTransferNet: expected attributes [N, 3]");
  const std::int64_t n = x.size(0);
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2), s3 = pooled_size(c, 3);

  // Encoder: [N,T,H,W] -> [N,C1,H1,W1] -> [N,C2,H2,W2] -> [N,C3,H3,W3]
  auto e1 = torch::relu(bn1(conv1(x)));
  auto [p1, i1] = pool->forward_with_indices(e1);
  auto e2 = torch::relu(bn2(conv2(p1)));
  auto [p2, i2] = pool->forward_with_indices(e2);
  auto e3 = torch::relu(bn3(conv3(p2)));
  auto [p3, i3] = pool->forward_with_indices(e3);
  auto h = torch::relu(fc_features(p3.flatten(1)));                 // [N, hidden]
  auto z = fc_latent(torch::cat({h, source}, 1));                    // [N, latent]

  // Decoder: [N, latent + A] -> [N,C3,H3,W3] -> ... -> [N,T,H,W]
  auto d = torch::relu(fc_decode(torch::cat({z, target}, 1)));
  d = d.view({n, c.channels[2], s3[0], s3[1]});
  d = torch::max_unpool2d(d, i3, {s2[0], s2[1]});            // [N,C3,H2,W2]
  if (has_skips(c.arch)) d = torch::cat({d, e3}, 1);
  d = torch::relu(dbn3(deconv3(d)));                                 // [N,C2,H2,W2]
  d = torch::max_unpool2d(d, i2, {s1[0], s1[1]});            // [N,C2,H1,W1]
  if (has_skips(c.arch)) d = torch::cat({d, e2}, 1);
  d = torch::relu(dbn2(deconv2(d)));                                 // [N,C1,H1,W1]
  d = torch::max_unpool2d(d, i1, {s0[0], s0[1]});            // [N,C1,H,W]
  if (has_skips(c.arch)) d = torch::cat({d, e1}, 1);
  auto out = deconv1(d);                                             // [N,T,H,W] pre-activation
  if (c.arch == Arch::residual) out = out + x;                       // a correction to the source
  return out;
}

std::int64_t parameter_count(const torch::nn::Module& module) {
  std::int64_t n = 0;
  for (const auto& p : module.parameters()) n += p.numel();
  return n;
}

void write_weights(const PressureTransferNet& net, torch::serialize::OutputArchive& archive) {
  // Flat names: "conv1.weight", "bn1.running_mean", ...
  for (const auto& item : net->named_parameters(/*recurse=*/true))
    archive.write(item.key(), item.value().detach().cpu(), /*is_buffer=*/false);
  for (const auto& item : net->named_buffers(/*recurse=*/true))
    archive.write(item.key(), item.value().cpu(), /*is_buffer=*/true);
}

void read_weights(PressureTransferNet& net, torch::serialize::InputArchive& archive,
                  const std::string& path) {
  torch::NoGradGuard no_grad;
  auto load_one = [&](const std::string& name, torch::Tensor& dst, bool buffer) {
    torch::Tensor src;
    if (!archive.try_read(name, src, buffer))
      throw Error::in(path, "missing tensor \"" + name + "\" (built for another architecture?)");
    if (src.sizes() != dst.sizes()) {
      std::ostringstream s;
      s << "tensor \"" << name << "\" has shape " << src.sizes() << ", the model expects "
        << dst.sizes() << " (weights and config.json disagree)";
      throw Error::in(path, s.str());
    }
    dst.copy_(src);
  };
  for (auto& item : net->named_parameters(/*recurse=*/true)) load_one(item.key(), item.value(), false);
  for (auto& item : net->named_buffers(/*recurse=*/true)) load_one(item.key(), item.value(), true);
}

void save_weights(const PressureTransferNet& net, const std::string& path) {
  AtomicFile out(path, /*force=*/true);
  torch::serialize::OutputArchive archive;
  write_weights(net, archive);
  archive.save_to(out.temp_path());
  out.commit();
}

void load_weights(PressureTransferNet& net, const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error::in(path, "no such file (model weights)");
  verify_zip_file(path);
  torch::serialize::InputArchive archive;
  try {
    archive.load_from(path, torch::kCPU);
  } catch (const c10::Error&) {
    throw Error::in(path, "not a ptnet weights file (corrupt or truncated)");
  }
  read_weights(net, archive, path);
}

torch::Device parse_device(const std::string& text) {
  if (text == "cpu") return torch::kCPU;
  if (text == "cuda") {
    if (!torch::cuda::is_available())
      throw Error("--device cuda: this LibTorch build or machine has no CUDA device; use --device cpu");
    return torch::kCUDA;
  }
  throw Error("--device: expected cpu or cuda, found \"" + text + "\"");
}

}  // namespace ptnet
