// InferenceNet: a trained PressureTransferNet for inference only (model.hpp).
//
// Dimension legend: N windows, T window frames, M = N x T frames (Arch::frame),
// K = 1 + 2 context input frames (x holds T + 2 context), H x W mat cells, A = 3 attributes,
// C1..C3 conv widths, F = FiLM width (gamma and beta of every block).
//
// What it skips against the module's forward() in eval mode:
// - every eval-mode BatchNorm is folded into the convolution before it
//   (W' = W s, b' = (b - mean) s + beta, s = gamma / sqrt(var + eps));
// - Arch::frame with one body pair per call (transfer, stream): the FiLM
//   modulation (1 + gamma, beta) is folded too, once per pair (cached), so a
//   block is one convolution and a ReLU;
// - Arch::frame: the 1x1 laterals run before the nearest upsampling (they
//   commute; 4x fewer multiply-adds);
// - window archs: each ConvTranspose2d runs as the equivalent Conv2d;
// - activations in channels-last layout (measured faster, bench_model), the
//   single-channel kernels too (in_format); batches in chunks whose widest
//   activation stays below kInferenceChunkBytes (chunk_windows);
// - autograd bookkeeping (torch::InferenceMode).
#include <algorithm>
#include <cmath>

#include "model/model_config_internal.hpp"
#include "model/model_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model.hpp"

namespace ptnet {
namespace {

// The net's tensors by their state-dict names ("conv1.weight").
struct Named {
  torch::OrderedDict<std::string, torch::Tensor> params, buffers;
  explicit Named(const PressureTransferNet& net)
      : params(net->named_parameters(true)), buffers(net->named_buffers(true)) {}
  torch::Tensor operator()(const std::string& name) const {
    if (const auto* p = params.find(name)) return p->detach().clone();
    if (const auto* b = buffers.find(name)) return b->detach().clone();
    throw Error("InferenceNet: the network has no tensor \"" + name + "\"");
  }
  bool has(const std::string& name) const { return params.contains(name) || buffers.contains(name); }
};

constexpr double kBatchNormEps = 1e-5;  // torch::nn::BatchNorm2d's default, used by every norm of the net

// Per-channel scale and shift of an eval-mode BatchNorm named `bn` ([C] each).
std::pair<torch::Tensor, torch::Tensor> norm_affine(const Named& n, const std::string& bn) {
  auto scale = torch::rsqrt(n(bn + ".running_var") + kBatchNormEps);
  auto shift = -n(bn + ".running_mean") * scale;
  if (n.has(bn + ".weight")) {
    shift = shift * n(bn + ".weight") + n(bn + ".bias");
    scale = scale * n(bn + ".weight");
  }
  return {scale, shift};
}

// Arch::frame's output, one pass over the cells: ReLU(frame + correction),
// and with a contact head 0 where the logit is < 0, else at least `floor`
// (PressureTransferNetImpl::contact_output). x [N,T,H,W]; out [M,1+contact,H,W]
// (correction, logit) -> [N,T,H,W].
torch::Tensor frame_outputs(const torch::Tensor& x, const torch::Tensor& out, bool contact, float floor) {
  const auto n = x.size(0), t = x.size(1), h = x.size(2), w = x.size(3);  // x: the centre frames
  auto head = out.contiguous();                                                        // [M,1+contact,H,W]
  auto in = x.contiguous();                                                            // [N,T,H,W]
  auto y = torch::empty({n, t, h, w}, x.options());
  const int64_t count = n * t, cells = h * w, outs = head.size(1);
  const float* hp = head.data_ptr<float>();
  const float* xp = in.data_ptr<float>();
  float* yp = y.data_ptr<float>();
  for (int64_t f = 0; f < count; ++f) {
    const float* correction = hp + f * outs * cells;
    const float* logit = correction + cells;
    for (int64_t i = 0; i < cells; ++i) {
      const float p = std::max(xp[f * cells + i] + correction[i], 0.0f);
      yp[f * cells + i] = !contact ? p : logit[i] > 0 ? std::max(p, floor) : 0.0f;
    }
  }
  return y;
}

}  // namespace

// `t` [N,C,H,W] copied into `format` with that format's strides even where
// they are ambiguous: with one channel ([16, 1, 3, 3], the frame network's
// first kernel), the NCHW strides are also channels-last contiguous, so
// contiguous(ChannelsLast) keeps them and LibTorch then reads the tensor as
// NCHW; a convolution with such a weight (and such an input) writes NCHW, and
// every layer after it pays for the mixed layouts (the frame network's first
// pooling 5x slower; measured, docs/model.md "Speed").
torch::Tensor in_format(const torch::Tensor& t, at::MemoryFormat format) {
  return torch::empty(t.sizes(), t.options().memory_format(format)).copy_(t);
}

int64_t chunk_windows(const ModelConfig& c, int64_t n, int64_t budget_bytes) {
  // Channels of the widest activation at full resolution, per window.
  const int64_t c1 = c.channels[0];
  const int64_t widest = c.arch == Arch::frame ? int64_t(c.window) * std::max<int64_t>(1 + 2 * c.context, c1)
                                               : std::max<int64_t>(c.window, has_skips(c.arch) ? 2 * c1 : c1);
  const int64_t bytes = widest * c.rows * c.cols * int64_t(sizeof(float));
  const int64_t per_chunk = std::max<int64_t>(1, budget_bytes / bytes);
  const int64_t chunks = (n + per_chunk - 1) / per_chunk;
  return chunks <= 1 ? n : (n + chunks - 1) / chunks;
}

InferenceNet::InferenceNet(const PressureTransferNet& net, MemoryLayout layout) : config_(net->config()) {
  TORCH_CHECK(!net->is_training(), "InferenceNet: the network must be in eval mode");
  if (layout == MemoryLayout::automatic) layout = MemoryLayout::channels_last;  // measured: BM_InferenceLayout
  format_ = layout == MemoryLayout::channels_last ? at::MemoryFormat::ChannelsLast : at::MemoryFormat::Contiguous;
  torch::NoGradGuard no_grad;
  const Named n(net);
  auto conv = [&](const std::string& c, const std::string& bn, bool transposed) {
    // Conv2d weight [out, in, 3, 3]; ConvTranspose2d weight [in, out, 3, 3].
    auto w = n(c + ".weight");
    auto b = n.has(c + ".bias") ? n(c + ".bias") : torch::zeros({w.size(transposed ? 1 : 0)});
    // A stride-1 ConvTranspose2d (padding 1, 3x3) is the Conv2d with the
    // kernel's in/out swapped and flipped; Conv2d measured 1.3x faster.
    if (transposed) w = w.transpose(0, 1).flip({2, 3});
    if (bn.empty()) return Layer{in_format(w, format_), b};
    auto [scale, shift] = norm_affine(n, bn);
    return Layer{in_format(w * scale.view({-1, 1, 1, 1}), format_), b * scale + shift};
  };
  if (config_.arch == Arch::frame) {
    for (int i = 0; i < 6; ++i) {
      const std::string c = "frame.conv" + std::to_string(i);
      layers_.push_back(conv(c, "frame.norm" + std::to_string(i), false));
    }
    layers_.push_back(conv("frame.lateral1", "", false));
    layers_.push_back(conv("frame.lateral0", "", false));
    layers_.push_back(conv("frame.head", "", false));
    film1_ = {n("frame.film1.weight"), n("frame.film1.bias")};
    film2_ = {n("frame.film2.weight"), n("frame.film2.bias")};
    if (config_.contact) contact_floor_ = n("contact_floor");
    return;
  }
  layers_ = {conv("conv1", "bn1", false),       conv("conv2", "bn2", false),       conv("conv3", "bn3", false),
             conv("deconv3", "dbn3", true),     conv("deconv2", "dbn2", true),     conv("deconv1", "", true),
             {n("fc_features.weight"), n("fc_features.bias")}, {n("fc_latent.weight"), n("fc_latent.bias")},
             {n("fc_decode.weight"), n("fc_decode.bias")}};
}

torch::Tensor InferenceNet::forward(const torch::Tensor& x, const torch::Tensor& source,
                                    const torch::Tensor& target) {
  const auto& c = config_;
  const bool any_size = c.arch == Arch::frame && x.dim() == 4;
  TORCH_CHECK(any_size || (x.dim() == 4 && x.size(1) == c.window && x.size(2) == c.rows && x.size(3) == c.cols),
              "InferenceNet: expected input [N, ", c.window, ", ", c.rows, ", ", c.cols, "], found ", x.sizes());
  TORCH_CHECK(source.dim() == 2 && source.size(1) == kAttributes && target.sizes() == source.sizes() &&
                  source.size(0) == x.size(0),
              "InferenceNet: expected attributes [N, 3]");
  torch::InferenceMode guard;
  auto run = [&](const torch::Tensor& xs, const torch::Tensor& ss, const torch::Tensor& ts) {
    if (c.arch == Arch::frame) return forward_frame(xs, ss, ts);
    return forward_window(xs.contiguous(format_), ss, ts).contiguous();
  };
  const auto n = x.size(0);
  const auto chunk = chunk_windows(c, n, kInferenceChunkBytes);
  if (n <= chunk) return run(x, source, target);
  std::vector<torch::Tensor> parts;
  for (int64_t i = 0; i < n; i += chunk) {
    const auto m = std::min<int64_t>(chunk, n - i);
    parts.push_back(run(x.narrow(0, i, m), source.narrow(0, i, m), target.narrow(0, i, m)));
  }
  return torch::cat(parts);
}

torch::Tensor InferenceNet::forward_window(const torch::Tensor& x, const torch::Tensor& source,
                                           const torch::Tensor& target) const {
  const auto& c = config_;
  const auto& L = layers_;
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2), s3 = pooled_size(c, 3);
  const bool skips = has_skips(c.arch);
  auto conv = [](const torch::Tensor& t, const Layer& l) { return torch::conv2d(t, l.weight, l.bias, 1, 1); };
  auto deconv = [&](const torch::Tensor& t, const Layer& l) { return conv(t.contiguous(format_), l); };
  auto pool = [](const torch::Tensor& t) { return torch::max_pool2d_with_indices(t, 2, 2, 0, 1, true); };
  // Encoder: [N,T,H,W] -> [N,C1,H1,W1] -> [N,C2,H2,W2] -> [N,C3,H3,W3]
  auto e1 = conv(x, L[0]).relu_();
  auto [p1, i1] = pool(e1);
  auto e2 = conv(p1, L[1]).relu_();
  auto [p2, i2] = pool(e2);
  auto e3 = conv(p2, L[2]).relu_();
  auto [p3, i3] = pool(e3);
  auto h = torch::linear(p3.flatten(1), L[6].weight, L[6].bias).relu_();       // [N, hidden]
  auto z = torch::linear(torch::cat({h, source}, 1), L[7].weight, L[7].bias);        // [N, latent]
  // Decoder
  auto d = torch::linear(torch::cat({z, target}, 1), L[8].weight, L[8].bias).relu_();
  d = d.view({x.size(0), c.channels[2], s3[0], s3[1]});
  d = torch::max_unpool2d(d, i3, {s2[0], s2[1]});                                     // [N,C3,H2,W2]
  if (skips) d = torch::cat({d, e3}, 1);
  d = deconv(d, L[3]).relu_();                                                  // [N,C2,H2,W2]
  d = torch::max_unpool2d(d, i2, {s1[0], s1[1]});
  if (skips) d = torch::cat({d, e2}, 1);
  d = deconv(d, L[4]).relu_();                                                  // [N,C1,H1,W1]
  d = torch::max_unpool2d(d, i1, {s0[0], s0[1]});
  if (skips) d = torch::cat({d, e1}, 1);
  auto out = deconv(d, L[5]);                                                         // [N,T,H,W]
  if (is_residual(c.arch)) out = out + x;
  return out.relu_();
}

// One body pair for every frame: FiLM folded into the BN-folded weights
// (cached per pair). Mixed pairs: FiLM applied per frame.
torch::Tensor InferenceNet::forward_frame(const torch::Tensor& x, const torch::Tensor& source,
                                          const torch::Tensor& target) {
  const auto& c = config_;
  const auto n = x.size(0), t = x.size(1) - 2 * c.context;  // t output frames
  // One body pair for all windows? Read on the host: a few floats, no tensor ops.
  const auto src = source.contiguous(), dst = target.contiguous();
  const float *sp = src.data_ptr<float>(), *dp = dst.data_ptr<float>();
  std::vector<float> key(sp, sp + kAttributes);
  key.insert(key.end(), dp, dp + kAttributes);
  bool one_pair = true;
  for (int64_t i = 1; i < n && one_pair; ++i)
    one_pair = std::equal(sp, sp + kAttributes, sp + i * kAttributes) &&
               std::equal(dp, dp + kAttributes, dp + i * kAttributes);
  auto film_of = [&](const torch::Tensor& cond) {                                      // [*, 2A] -> [*, F]
    auto hdn = torch::linear(cond, film1_.weight, film1_.bias).relu_();
    return torch::linear(hdn, film2_.weight, film2_.bias);
  };
  torch::Tensor film;  // [M, F], only for mixed pairs
  if (one_pair) {
    if (key != pair_key_) {
      auto f = film_of(torch::cat({src.narrow(0, 0, 1), dst.narrow(0, 0, 1)}, 1))[0];  // [F]
      folded_.clear();
      int offset = 0;
      for (int i = 0; i < 6; ++i) {
        const auto width = layers_[std::size_t(i)].weight.size(0);
        auto g = 1 + f.narrow(0, offset, width);
        auto shift = f.narrow(0, offset + width, width);
        folded_.push_back({in_format(layers_[std::size_t(i)].weight * g.view({-1, 1, 1, 1}), format_),
                           layers_[std::size_t(i)].bias * g + shift});
        offset += int(2 * width);
      }
      pair_key_ = std::move(key);
    }
  } else {
    film = film_of(torch::cat({src, dst}, 1)).repeat_interleave(t, 0);
    pair_key_.clear();
  }
  std::vector<int> offsets;  // FiLM column of each block (mixed pairs)
  for (int i = 0, o = 0; i < 6; ++i) {
    offsets.push_back(o);
    o += int(2 * layers_[std::size_t(i)].weight.size(0));
  }
  auto block = [&](int i, const torch::Tensor& in) {
    if (one_pair) {
      const Layer& l = folded_[std::size_t(i)];
      return torch::conv2d(in, l.weight, l.bias, 1, 1).relu_();
    }
    const Layer& l = layers_[std::size_t(i)];
    const auto width = l.weight.size(0);
    auto g = film.narrow(1, offsets[std::size_t(i)], width).unsqueeze(2).unsqueeze(3);
    auto b = film.narrow(1, offsets[std::size_t(i)] + width, width).unsqueeze(2).unsqueeze(3);
    return (torch::conv2d(in, l.weight, l.bias, 1, 1) * (1 + g) + b).relu_();
  };
  auto pool = [](const torch::Tensor& in) { return torch::max_pool2d(in, 2, 2, 0, 1, true); };
  auto lateral_up = [&](const Layer& l, const torch::Tensor& in, const torch::Tensor& like) {
    // 1x1 convolution, then nearest upsampling to like's size (they commute)
    return torch::upsample_nearest2d(torch::conv2d(in, l.weight, l.bias), {like.size(2), like.size(3)});
  };
  const torch::Tensor frames = frame_inputs(x, c.context).contiguous(format_);        // [M,K,H,W]
  auto e0 = block(0, frames);                                                          // [M,C1,H,W]
  auto e1 = block(1, pool(e0));                                                        // [M,C2,H1,W1]
  auto e2 = block(2, pool(e1));                                                        // [M,C3,H2,W2]
  auto m = block(3, e2);                                                               // [M,C3,H2,W2]
  auto d1 = block(4, lateral_up(layers_[6], m, e1).add_(e1));                          // [M,C2,H1,W1]
  auto d0 = block(5, lateral_up(layers_[7], d1, e0).add_(e0));                         // [M,C1,H,W]
  auto out = torch::conv2d(d0, layers_[8].weight, layers_[8].bias, 1, 1);             // [M,1+contact,H,W]
  return frame_outputs(x.narrow(1, c.context, t), out, c.contact, c.contact ? contact_floor_.item<float>() : 0.0f);
}

}  // namespace ptnet
