// InferenceNet (BatchNorm and FiLM folded, InferenceMode) equals the module's
// eval-mode forward within float rounding, for every architecture, one body
// pair or mixed pairs, and after the pair changes (the cache).
#include <gtest/gtest.h>

#include "ptnet/model.hpp"

using namespace ptnet;

namespace {

// Tolerance of the folded network: relative to the output's largest value.
// Folding reorders float32 products (W s instead of (W x) s); measured
// differences are ~1e-6 of the output's range.
constexpr float kFoldTolerance = 1e-4f;

ModelConfig small(Arch arch) {
  ModelConfig c;
  c.arch = arch;
  c.channels = {4, 8, 8};
  c.hidden = 16;
  c.latent = 16;
  if (arch == Arch::frame) {
    c.window = 3;
    c.context = 1;
    c.contact = true;
  }
  return c;
}

// A network whose every weight and BatchNorm statistic is non-trivial (the
// zero-initialised heads and FiLM layers included), in eval mode.
PressureTransferNet random_net(const ModelConfig& c) {
  torch::manual_seed(7);
  PressureTransferNet net(c);
  torch::NoGradGuard no_grad;
  for (auto& p : net->named_parameters()) p.value().copy_(torch::randn_like(p.value()) * 0.3);
  for (auto& b : net->named_buffers()) {
    if (b.key().find("running_var") != std::string::npos) b.value().copy_(torch::rand_like(b.value()) + 0.5);
    if (b.key().find("running_mean") != std::string::npos) b.value().copy_(torch::randn_like(b.value()) * 0.2);
  }
  if (c.contact) net->set_contact_floor(0.05);
  net->eval();
  return net;
}

void expect_close(const torch::Tensor& ref, const torch::Tensor& fast, const std::string& what) {
  ASSERT_EQ(ref.sizes(), fast.sizes()) << what;
  const float scale = std::max(1.0f, ref.abs().max().item<float>());
  EXPECT_LE((ref - fast).abs().max().item<float>(), kFoldTolerance * scale) << what;
}

}  // namespace

TEST(ModelInference, FoldedEqualsModuleEveryArchitecture) {
  for (Arch arch : {Arch::faithful, Arch::skip, Arch::residual, Arch::frame}) {
    const ModelConfig c = small(arch);
    PressureTransferNet net = random_net(c);
    InferenceNet fast(net);
    auto x = torch::rand({3, c.window, c.rows, c.cols});
    auto one = torch::randn({1, 3}).expand({3, 3}).contiguous();
    auto mixed = torch::randn({3, 3});
    auto other = torch::randn({3, 3});
    torch::NoGradGuard no_grad;
    expect_close(net->forward(x, one, one.flip(1)), fast.forward(x, one, one.flip(1)),
                 std::string(arch_name(arch)) + " one pair");
    expect_close(net->forward(x, mixed, other), fast.forward(x, mixed, other),
                 std::string(arch_name(arch)) + " mixed pairs");
    // Another pair after a cached one, then the first again.
    auto two = torch::randn({1, 3}).expand({3, 3}).contiguous();
    expect_close(net->forward(x, two, one), fast.forward(x, two, one), std::string(arch_name(arch)) + " new pair");
    expect_close(net->forward(x, one, one.flip(1)), fast.forward(x, one, one.flip(1)),
                 std::string(arch_name(arch)) + " first pair again");
  }
}

TEST(ModelInference, FramePresetShapeAnyLengthAndNoContext) {
  ModelConfig c = small(Arch::frame);
  c.window = 1;
  c.context = 0;
  c.channels = {16, 32, 48};
  c.hidden = 64;
  PressureTransferNet net = random_net(c);
  InferenceNet fast(net);
  auto a = torch::randn({1, 3});
  for (int frames : {1, 5}) {
    auto x = torch::rand({frames, 1, c.rows, c.cols});
    torch::NoGradGuard no_grad;
    expect_close(net->forward(x, a.expand({frames, 3}), a.flip(1).expand({frames, 3})),
                 fast.forward(x, a.expand({frames, 3}), a.flip(1).expand({frames, 3})), "frames " + std::to_string(frames));
  }
}

TEST(ModelInference, NeedsEvalModeAndRightShapes) {
  PressureTransferNet net(small(Arch::faithful));
  net->train();
  EXPECT_THROW(InferenceNet{net}, c10::Error);
  net->eval();
  InferenceNet fast(net);
  EXPECT_THROW(fast.forward(torch::rand({2, 30, 64, 28}), torch::zeros({2, 3}), torch::zeros({2, 3})), c10::Error);
}

TEST(ModelInference, LargeBatchesRunInChunksWithTheSameResult) {
  for (Arch arch : {Arch::skip, Arch::frame}) {
    const ModelConfig c = small(arch);
    PressureTransferNet net = random_net(c);
    InferenceNet fast(net);
    auto x = torch::rand({19, c.window, c.rows, c.cols});  // 8 + 8 + 3 windows
    auto a = torch::randn({1, 3}).expand({19, 3});
    auto mixed = torch::randn({19, 3});
    torch::NoGradGuard no_grad;
    expect_close(net->forward(x, a, mixed), fast.forward(x, a, mixed), std::string(arch_name(arch)) + " batch 19");
    expect_close(net->forward(x, a, a), fast.forward(x, a, a), std::string(arch_name(arch)) + " batch 19, one pair");
  }
}
