// ptnet/model.hpp: PressureTransferNet (the paper's encoder-decoder) in LibTorch.
//
//   ptnet::PressureTransferNet net(ptnet::ModelConfig::paper());
//   auto y = net->forward(x, source_attrs, target_attrs);  // [N, 30, 80, 28] >= 0
//   ptnet::save_weights(net, "model/model.pt");
//
// Dimension legend: N windows, T = window (30) frames as channels, H x W = mat
// rows x cols (80 x 28), A = 3 attributes (sex, z(height), z(weight)),
// C1..C3 conv widths, (Hk, Wk) = spatial size after k poolings
// (80x28 -> 40x14 -> 20x7 -> 10x4, ceil halving).
//
// Encoder (the paper's 11 layers): 3 x [Conv2d 3x3, BatchNorm2d, ReLU,
// MaxPool 2x2 (ceil, indices kept)], flatten, FC -> hidden (128) + ReLU,
// concat source attributes, FC -> latent (128).
// Decoder: concat target attributes, FC -> C3 x H3 x W3 + ReLU, then 3 mirrored
// blocks [MaxUnpool2d with the encoder's indices, ConvTranspose2d 3x3,
// BatchNorm2d, ReLU]; the last block has no BatchNorm and ends in ReLU so the
// output (normalised pressure) is non-negative. Arch::skip also concatenates
// the encoder block's pre-pool feature map before each ConvTranspose2d.
//
// Arch::frame (ours) is a different network behind the same interface
// (FrameNetImpl below): each of the T frames of a window goes through a
// conditional U-Net on its own, with `context` frames on each side as extra
// input channels, and the result is added to the frame. Its input window
// carries those neighbours: x [N, T + 2 context, H, W] -> [N, T, H, W]
// (input_margin, model_config.hpp; a whole sequence is padded with copies
// of its first and last frames).
// Every convolution is followed by BatchNorm (no affine) and a FiLM
// modulation (1 + gamma, beta) computed by a small MLP from the source
// and target attributes, so the body attributes act at every scale:
//   enc0 K->C1 (H x W), pool, enc1 C1->C2 (H1 x W1), pool, enc2 C2->C3 and
//   mid C3->C3 (H2 x W2); dec1: upsample, 1x1 C3->C2 + enc1, C2->C2;
//   dec0: upsample, 1x1 C2->C1 + enc0, C1->C1; head 3x3 C1->1 (zero-init),
//   or C1->2 with a contact head (ModelConfig::contact): the second channel
//   is the logit that the cell is in contact.
//
// Only the model and train stages include this header (it pulls in Torch).
#pragma once

#include <torch/torch.h>

#include <string>

#include "ptnet/model_config.hpp"

namespace ptnet {

// Arch::frame's network: frames [M, K, H, W] (K = 1 + 2 context, the centre
// frame in the middle), conditions [M, 2A] (source, target attributes) ->
// [M, 1 + contact, H, W]: the correction (normalised pressure, any sign) and,
// with a contact head, the contact logit.
class FrameNetImpl : public torch::nn::Module {
 public:
  explicit FrameNetImpl(const ModelConfig& config);
  torch::Tensor forward(const torch::Tensor& frames, const torch::Tensor& conditions);

 private:
  // conv 3x3 (no bias), BatchNorm (no affine), FiLM with film[:, offset...], ReLU
  torch::Tensor block(int i, const torch::Tensor& x, const torch::Tensor& film);
  std::vector<torch::nn::Conv2d> convs_;          // enc0, enc1, enc2, mid, dec1, dec0
  std::vector<torch::nn::BatchNorm2d> norms_;
  std::vector<int> film_offset_;                  // first gamma column of each block in the FiLM output
  torch::nn::Conv2d lateral1{nullptr}, lateral0{nullptr}, head{nullptr};
  torch::nn::Linear film1{nullptr}, film2{nullptr};
  torch::nn::MaxPool2d pool{nullptr};
};
TORCH_MODULE(FrameNet);

class PressureTransferNetImpl : public torch::nn::Module {
 public:
  explicit PressureTransferNetImpl(const ModelConfig& config);

  // x [N, T + 2 m, H, W] normalised pressure (m = input_margin(config):
  // the context frames before the first and after the last output frame);
  // source, target [N, A] normalised attributes -> [N, T, H, W] normalised
  // pressure, >= 0.
  torch::Tensor forward(const torch::Tensor& x, const torch::Tensor& source,
                        const torch::Tensor& target);
  // The same before the output ReLU ([N, T, H, W], any sign): training uses
  // it so that cells whose truth is > 0 keep a gradient even where the
  // output is clamped at 0 (a plain ReLU output dies on sparse maps).
  torch::Tensor forward_raw(const torch::Tensor& x, const torch::Tensor& source,
                            const torch::Tensor& target);
  // forward_raw and, with a contact head, the contact logits [N, T, H, W]
  // (undefined without one): what training needs for both losses.
  struct Raw {
    torch::Tensor pressure, contact;
  };
  Raw forward_parts(const torch::Tensor& x, const torch::Tensor& source, const torch::Tensor& target);
  // The output of a contact-head model: 0 where `contact` < 0, else
  // max(ReLU(pressure), contact_floor) (forward() = this of forward_parts()).
  torch::Tensor contact_output(const Raw& raw) const;
  // The smallest pressure (normalised) a contact cell is given: the training
  // data's smallest reading, set by training and stored with the weights.
  void set_contact_floor(double floor);

  const ModelConfig& config() const { return config_; }

 private:
  ModelConfig config_;
  torch::nn::Conv2d conv1, conv2, conv3;
  torch::nn::BatchNorm2d bn1, bn2, bn3;
  torch::nn::MaxPool2d pool;
  torch::nn::Linear fc_features, fc_latent, fc_decode;
  torch::nn::ConvTranspose2d deconv3, deconv2, deconv1;
  torch::nn::BatchNorm2d dbn3, dbn2;
  FrameNet frame{nullptr};  // Arch::frame only (the layers above are then empty)
  torch::Tensor contact_floor_;  // buffer "contact_floor" (contact head only): scalar, normalised
};
TORCH_MODULE(PressureTransferNet);

// A trained network for inference only (src/model/inference.cpp): a copy of
// the weights with every eval-mode BatchNorm folded into its convolution and,
// for Arch::frame with one (source, target) pair per call, the FiLM
// modulation folded too (cached per pair), run under torch::InferenceMode.
// forward() equals net->forward() of the eval-mode module within float
// rounding (tested: model_inference_test); the module stays the reference
// and the only path for training.
//
//   net->eval();
//   ptnet::InferenceNet fast(net);
//   auto y = fast.forward(x, source, target);   // [N, T, H, W] >= 0, as net->forward
// Memory layout of the activations: channels-last (NHWC) measured faster for
// every architecture at batch 1 and 64, one thread (bench_model BM_InferenceLayout,
// docs/model.md "Speed"); `automatic` picks the measured one.
enum class MemoryLayout { automatic, contiguous, channels_last };

class InferenceNet {
 public:
  explicit InferenceNet(const PressureTransferNet& net,  // net in eval mode
                        MemoryLayout layout = MemoryLayout::automatic);
  // x [N, T + 2 m, H, W], source, target [N, A] -> [N, T, H, W] normalised
  // pressure >= 0 (m = input_margin, as the module's forward).
  torch::Tensor forward(const torch::Tensor& x, const torch::Tensor& source, const torch::Tensor& target);
  const ModelConfig& config() const { return config_; }

 private:
  struct Layer {
    torch::Tensor weight, bias;
  };
  torch::Tensor forward_window(const torch::Tensor& x, const torch::Tensor& source,
                               const torch::Tensor& target) const;
  torch::Tensor forward_frame(const torch::Tensor& x, const torch::Tensor& source, const torch::Tensor& target);
  ModelConfig config_;
  at::MemoryFormat format_ = at::MemoryFormat::Contiguous;
  // window archs: conv1-3, deconv3, deconv2, deconv1, fc_features, fc_latent, fc_decode;
  // Arch::frame: conv0-5 (BN folded), lateral1, lateral0, head
  std::vector<Layer> layers_;
  Layer film1_, film2_;
  torch::Tensor contact_floor_;
  std::vector<float> pair_key_;   // the (source, target) attributes folded_ is for
  std::vector<Layer> folded_;     // conv0-5 with BN and FiLM folded
};

// ModelConfig::mirror: (forward(x) + mirror(forward(mirror(x)))) / 2, mirror
// the flip of the last dimension (the mat's columns). `forward` maps
// [N, T, H, W] -> [N, T, H, W]. The one place inference and validation average.
template <class Forward>
torch::Tensor mirror_averaged(const Forward& forward, const torch::Tensor& x) {
  return forward(x).add(forward(x.flip({-1})).flip({-1})).mul_(0.5);
}

// Trainable parameters of a module.
std::int64_t parameter_count(const torch::nn::Module& module);

// Weights (parameters and buffers) to/from a file; load verifies the
// archive's CRC-32s (zip_check.hpp), checks names and shapes and throws Error
// naming the file on mismatch.
void save_weights(const PressureTransferNet& net, const std::string& path);
void load_weights(PressureTransferNet& net, const std::string& path);
// The same into/out of an archive (checkpoints); `path` names it in errors.
void write_weights(const PressureTransferNet& net, torch::serialize::OutputArchive& archive);
void read_weights(PressureTransferNet& net, torch::serialize::InputArchive& archive,
                  const std::string& path);

// Integrity (src/model/integrity.cpp): FNV-1a 64 (16 hex digits) over every
// parameter and buffer (name, shape, float32 bytes) in registration order.
std::string weights_digest(const torch::nn::Module& net);
// Throws Error "PATH: weights do not match the digest in DIR/config.json
// (corrupt or replaced file)" when `recorded` (a digest, or "") differs from
// the net's; an empty `recorded` (older models) passes.
void check_weights_digest(const torch::nn::Module& net, const std::string& recorded, const std::string& path,
                          const std::string& config_path);

// torch::Device from "cpu" | "cuda" (Error if CUDA is not available).
torch::Device parse_device(const std::string& text);

}  // namespace ptnet
