// PressureTransferNet module, weights I/O (state_dict.cpp: the same weights
// as a PyTorch state dict).
//
// Dimension legend: N windows, T frames (channels), H x W mat cells,
// A = 3 attributes, C1..C3 conv widths.
#include "ptnet/model.hpp"

#include <filesystem>
#include <sstream>

#include "core/zip_check.hpp"
#include "model/model_config_internal.hpp"
#include "model/model_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

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

// The window network's layers, or empty holders for Arch::frame.
template <typename Holder, typename... Args>
Holder layer(const ModelConfig& c, Args&&... args) {
  if (c.arch == Arch::frame) return Holder(nullptr);
  return Holder(std::forward<Args>(args)...);
}

PressureTransferNetImpl::PressureTransferNetImpl(const ModelConfig& config)
    : config_(checked(config)),
      conv1(layer<nn::Conv2d>(config, conv_options(config.window, config.channels[0]))),
      conv2(layer<nn::Conv2d>(config, conv_options(config.channels[0], config.channels[1]))),
      conv3(layer<nn::Conv2d>(config, conv_options(config.channels[1], config.channels[2]))),
      bn1(layer<nn::BatchNorm2d>(config, config.channels[0])),
      bn2(layer<nn::BatchNorm2d>(config, config.channels[1])),
      bn3(layer<nn::BatchNorm2d>(config, config.channels[2])),
      pool(layer<nn::MaxPool2d>(config, nn::MaxPool2dOptions(2).stride(2).ceil_mode(true))),
      fc_features(layer<nn::Linear>(config, flat_size(config), config.hidden)),
      fc_latent(layer<nn::Linear>(config, config.hidden + kAttributes, config.latent)),
      fc_decode(layer<nn::Linear>(config, config.latent + kAttributes, flat_size(config))),
      deconv3(layer<nn::ConvTranspose2d>(config, deconv_options(config.channels[2] * skip_factor(config), config.channels[1]))),
      deconv2(layer<nn::ConvTranspose2d>(config, deconv_options(config.channels[1] * skip_factor(config), config.channels[0]))),
      deconv1(layer<nn::ConvTranspose2d>(config, deconv_options(config.channels[0] * skip_factor(config), config.window))),
      dbn3(layer<nn::BatchNorm2d>(config, config.channels[1])),
      dbn2(layer<nn::BatchNorm2d>(config, config.channels[0])) {
  if (config.arch == Arch::frame) {
    frame = register_module("frame", FrameNet(config));
    if (config.contact) contact_floor_ = register_buffer("contact_floor", torch::zeros({}));
    return;
  }
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

// ------------------------------------------------------------ Arch::frame

namespace {
// Blocks of the frame U-Net: {input width, output width} from the config.
std::array<std::array<int, 2>, 6> frame_blocks(const ModelConfig& c) {
  const int k = 1 + 2 * c.context, c1 = c.channels[0], c2 = c.channels[1], c3 = c.channels[2];
  return {{{k, c1}, {c1, c2}, {c2, c3}, {c3, c3}, {c2, c2}, {c1, c1}}};  // enc0 enc1 enc2 mid dec1 dec0
}
}  // namespace

FrameNetImpl::FrameNetImpl(const ModelConfig& c) {
  int film_width = 0;
  int i = 0;
  for (const auto& [in, out] : frame_blocks(c)) {
    convs_.push_back(register_module("conv" + std::to_string(i),
                                     nn::Conv2d(nn::Conv2dOptions(in, out, 3).padding(1).bias(false))));
    norms_.push_back(register_module("norm" + std::to_string(i),
                                     nn::BatchNorm2d(nn::BatchNorm2dOptions(out).affine(false))));
    film_offset_.push_back(film_width);
    film_width += 2 * out;  // gamma, beta
    ++i;
  }
  lateral1 = register_module("lateral1", nn::Conv2d(nn::Conv2dOptions(c.channels[2], c.channels[1], 1)));
  lateral0 = register_module("lateral0", nn::Conv2d(nn::Conv2dOptions(c.channels[1], c.channels[0], 1)));
  head = register_module("head", nn::Conv2d(nn::Conv2dOptions(c.channels[0], c.contact ? 2 : 1, 3).padding(1)));
  film1 = register_module("film1", nn::Linear(2 * kAttributes, c.hidden));
  film2 = register_module("film2", nn::Linear(c.hidden, film_width));
  pool = register_module("pool", nn::MaxPool2d(nn::MaxPool2dOptions(2).stride(2).ceil_mode(true)));
  // Zero-initialised: an untrained model is its input, with FiLM the identity.
  torch::NoGradGuard no_grad;
  head->weight.zero_();
  head->bias.zero_();
  if (c.contact) head->bias[1].fill_(-2.0);  // most cells of a mat are empty
  film2->weight.zero_();
  film2->bias.zero_();
}

torch::Tensor FrameNetImpl::block(int i, const torch::Tensor& x, const torch::Tensor& film) {
  const int width = int(convs_[std::size_t(i)]->options.out_channels());
  const int o = film_offset_[std::size_t(i)];
  auto gamma = film.narrow(1, o, width).unsqueeze(2).unsqueeze(3);          // [M, C, 1, 1]
  auto beta = film.narrow(1, o + width, width).unsqueeze(2).unsqueeze(3);   // [M, C, 1, 1]
  auto y = norms_[std::size_t(i)](convs_[std::size_t(i)](x));
  return torch::relu(y * (1 + gamma) + beta);
}

torch::Tensor FrameNetImpl::forward(const torch::Tensor& frames, const torch::Tensor& conditions) {
  auto film = film2(torch::relu(film1(conditions)));                          // [M, F]
  auto size_of = [](const torch::Tensor& t) { return std::vector<int64_t>{t.size(2), t.size(3)}; };
  auto up = [&](const torch::Tensor& t, const torch::Tensor& like) {
    return torch::upsample_nearest2d(t, size_of(like));
  };
  auto e0 = block(0, frames, film);                                           // [M,C1,H,W]
  auto e1 = block(1, pool(e0), film);                                         // [M,C2,H1,W1]
  auto e2 = block(2, pool(e1), film);                                         // [M,C3,H2,W2]
  auto m = block(3, e2, film);                                                // [M,C3,H2,W2]
  auto d1 = block(4, lateral1(up(m, e1)) + e1, film);                         // [M,C2,H1,W1]
  auto d0 = block(5, lateral0(up(d1, e0)) + e0, film);                        // [M,C1,H,W]
  return head(d0);                                                            // [M,1+contact,H,W]
}

torch::Tensor frame_inputs(const torch::Tensor& x, int context) {
  const auto n = x.size(0), t = x.size(1) - 2 * context, h = x.size(2), w = x.size(3);
  TORCH_CHECK(t >= 1, "frame_inputs: a window of ", x.size(1), " frames has none inside its context of ", context);
  if (context == 0) return x.reshape({n * t, 1, h, w});
  auto u = x.unfold(1, 2 * context + 1, 1);                                     // [N,T,H,W,K]
  return u.permute({0, 1, 4, 2, 3}).reshape({n * t, 2 * context + 1, h, w});
}

torch::Tensor with_margin(const torch::Tensor& frames, int margin) {
  if (margin == 0) return frames;
  const auto t = frames.size(0), h = frames.size(1), w = frames.size(2);
  return torch::cat({frames.narrow(0, 0, 1).expand({margin, h, w}), frames,
                     frames.narrow(0, t - 1, 1).expand({margin, h, w})}, 0);  // [T+2m,H,W]
}

torch::Tensor PressureTransferNetImpl::forward(const torch::Tensor& x, const torch::Tensor& source,
                                               const torch::Tensor& target) {
  if (config_.contact) return contact_output(forward_parts(x, source, target));
  return torch::relu(forward_raw(x, source, target));  // [N,T,H,W] >= 0
}

torch::Tensor PressureTransferNetImpl::contact_output(const Raw& raw) const {
  auto p = torch::clamp_min(torch::relu(raw.pressure), contact_floor_);
  return torch::where(raw.contact > 0, p, torch::zeros_like(p));  // [N,T,H,W] >= 0
}

void PressureTransferNetImpl::set_contact_floor(double floor) {
  TORCH_CHECK(config_.contact && std::isfinite(floor) && floor >= 0, "set_contact_floor: no contact head or bad floor");
  torch::NoGradGuard no_grad;
  contact_floor_.fill_(floor);
}

torch::Tensor PressureTransferNetImpl::forward_raw(const torch::Tensor& x, const torch::Tensor& source,
                                                   const torch::Tensor& target) {
  return forward_parts(x, source, target).pressure;
}

PressureTransferNetImpl::Raw PressureTransferNetImpl::forward_parts(const torch::Tensor& x,
                                                                    const torch::Tensor& source,
                                                                    const torch::Tensor& target) {
  const auto& c = config_;
  // Arch::frame is fully convolutional and per frame: any number of frames and
  // any crop of the mat (training crops, whole sequences).
  const bool any_size = c.arch == Arch::frame && x.dim() == 4;
  TORCH_CHECK(any_size || (x.dim() == 4 && x.size(1) == c.window && x.size(2) == c.rows && x.size(3) == c.cols),
              "PressureTransferNet: expected input [N, ", c.window, ", ", c.rows, ", ", c.cols,
              "], found ", x.sizes());
  TORCH_CHECK(source.dim() == 2 && source.size(1) == kAttributes && target.sizes() == source.sizes() &&
                  source.size(0) == x.size(0),
              "PressureTransferNet: expected attributes [N, 3]");
  const std::int64_t n = x.size(0);
  if (c.arch == Arch::frame) {
    // Each frame on its own; the attributes repeated for the window's frames.
    const auto t = x.size(1) - 2 * c.context;
    auto conditions = torch::cat({source, target}, 1).repeat_interleave(t, 0);  // [N*T, 2A]
    auto out = frame(frame_inputs(x, c.context), conditions);                    // [N*T,1+contact,H,W]
    const std::vector<int64_t> shape{n, t, x.size(2), x.size(3)};
    Raw r{x.narrow(1, c.context, t) + out.select(1, 0).reshape(shape), torch::Tensor()};
    if (c.contact) r.contact = out.select(1, 1).reshape(shape);
    return r;
  }
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
  if (is_residual(c.arch)) out = out + x;                       // a correction to the source
  return {out, torch::Tensor()};
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
        << dst.sizes() << " (weights and " << ModelFiles::kConfig << " disagree)";
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
  if (!std::filesystem::exists(path, ec))
    throw Error::in(path, "no such file (model weights)", ErrorKind::not_found);
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
      throw Error(field_text("device") +
                  " cuda: this LibTorch build or machine has no CUDA device; use " +
                  field_text("device") + " cpu");
    return torch::kCUDA;
  }
  throw Error(field_text("device") + ": expected cpu or cuda, found \"" + text + "\"");
}

}  // namespace ptnet
