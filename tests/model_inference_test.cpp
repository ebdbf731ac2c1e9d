// InferenceNet (BatchNorm and FiLM folded, InferenceMode) equals the module's
// eval-mode forward within float rounding, for every architecture, one body
// pair or mixed pairs, and after the pair changes (the cache).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "model/model_internal.hpp"
#include "ptnet/model.hpp"
#include "ptnet/train.hpp"

using namespace ptnet;

namespace {

// Tolerance of the folded network: relative to the output's largest value.
// Folding reorders float32 products (W s instead of (W x) s); measured
// differences are ~1e-6 of the output's range under every instruction set
// (scripts/check-numerics.sh), away from max pooling's flips (flip_free_cells).
constexpr float kFoldTolerance = 1e-4f;
constexpr double kLambda = 8;  // rounding bound = 8 s: P(exceeded) <= 2 exp(-32) per value (flip_free_cells)

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

// Max pooling is discontinuous where the window architectures use it:
// max_unpool2d writes each decoded value where the encoder's 2x2 block had its
// maximum, so where two cells of a block lie within rounding of each other
// (or a cell's pre-activation within rounding of 0, the ReLU's zeros being
// exact ties), the folded and the module evaluation may pick different cells
// and the output there differs by a decoded value, not by rounding. (Seen
// with oneDNN's AVX2 kernels, DNNL_MAX_CPU_ISA=AVX2: skip 0.011 and 0.037 of
// an output of 1.5-2.5 in a few hundred cells; scripts/check-numerics.sh.)
//
// Which blocks can flip: the encoder is evaluated in float64 and each
// pre-activation a = BN(conv(e)) gets the rounding bound of a float32
// evaluation in any summation order, with or without FMA (the probabilistic
// analysis of python/tests/error_bound.py, Higham and Mary 2019): s^2 =
// n (u size)^2 + (W s_bn)^2 * s_in^2, n = 9 C_in + 16 roundings (the dot
// product, plus a slack for BatchNorm and its folding), u = 2^-24, size =
// |s_bn| (|W| * |e| + |b| + |mean|) + |beta| (s_bn the BatchNorm's scale),
// s_in the previous level's after pooling (max pooling and ReLU do not
// increase an error); a float32 value lies within kLambda s of the float64
// one. (The worst-case bound, gamma(n) size carried with |W|, is ~1e-3 of the
// activations at level 3, 1000x the error seen, and left 16 % of the cells.)
// A block is a candidate when a cell other than its float64 maximum can
// reach, within these bounds, the maximum's lower bound. A flip's effect on
// the output is bounded in space: a block at level k (k = 1..3) covers 2 rows and columns at resolution
// k - 1, each decoder convolution (3x3) widens by one cell, each unpooling
// doubles; every output frame of that window in that region is left out.
// Everywhere else both evaluations pool the same cells and differ by
// rounding only (kFoldTolerance).
torch::Tensor flip_free_cells(const PressureTransferNet& net, const torch::Tensor& x) {
  const ModelConfig& c = net->config();
  auto mask = torch::ones({x.size(0), c.rows, c.cols}, torch::kBool);
  if (c.arch == Arch::frame) return mask;  // max_pool2d without unpooling: continuous
  torch::NoGradGuard no_grad;
  const auto params = net->named_parameters(true);
  const auto buffers = net->named_buffers(true);
  auto get = [&](const std::string& k) {
    const auto* t = params.find(k);
    return (t ? *t : buffers[k]).detach().to(torch::kDouble);
  };
  const double u = std::ldexp(1.0, -24);
  torch::Tensor e = x.to(torch::kDouble), var = torch::zeros_like(e);
  auto acc = mask.accessor<bool, 3>();
  for (int level = 1; level <= 3; ++level) {
    const std::string k = std::to_string(level);
    auto w = get("conv" + k + ".weight"), b = get("conv" + k + ".bias");
    auto scale = get("bn" + k + ".weight") * torch::rsqrt(get("bn" + k + ".running_var") + 1e-5);
    auto view = [](const torch::Tensor& t) { return t.view({1, -1, 1, 1}); };
    auto mean = get("bn" + k + ".running_mean"), beta = get("bn" + k + ".bias");
    auto a = (torch::conv2d(e, w, b, 1, 1) - view(mean)) * view(scale) + view(beta);
    auto size = (torch::conv2d(e.abs(), w.abs(), b.abs(), 1, 1) + view(mean.abs())) * view(scale.abs()) +
                view(beta.abs());
    const double n = 9.0 * double(w.size(1)) + 16;
    var = n * (u * size).square() + torch::conv2d(var, w.square(), {}, 1, 1) * view(scale.square());
    const auto err = kLambda * var.sqrt();
    auto hi = (a + err).relu(), lo = (a - err).relu(), v = a.relu();
    auto H = hi.accessor<double, 4>(), L = lo.accessor<double, 4>(), V = v.accessor<double, 4>();
    const int64_t rows = a.size(2), cols = a.size(3);
    for (int64_t i = 0; i < a.size(0); ++i)
      for (int64_t ch = 0; ch < a.size(1); ++ch)
        for (int64_t r = 0; r < rows; r += 2)
          for (int64_t q = 0; q < cols; q += 2) {
            int64_t br = r, bq = q;  // the float64 maximum (the first of equals, as ATen)
            for (int64_t y = r; y < std::min(r + 2, rows); ++y)
              for (int64_t z = q; z < std::min(q + 2, cols); ++z)
                if (V[i][ch][y][z] > V[i][ch][br][bq]) br = y, bq = z;
            bool flip = false;
            for (int64_t y = r; y < std::min(r + 2, rows); ++y)
              for (int64_t z = q; z < std::min(q + 2, cols); ++z)
                if ((y != br || z != bq) && H[i][ch][y][z] > 0 && H[i][ch][y][z] >= L[i][ch][br][bq]) flip = true;
            if (!flip) continue;
            // The block's rows and columns at resolution level - 1, carried to the output.
            int64_t r0 = r - 1, r1 = r + 2, q0 = q - 1, q1 = q + 2;
            for (int res = level - 1; res > 0; --res) r0 = 2 * r0 - 1, r1 = 2 * r1 + 2, q0 = 2 * q0 - 1, q1 = 2 * q1 + 2;
            for (int64_t y = std::max<int64_t>(r0, 0); y <= std::min<int64_t>(r1, c.rows - 1); ++y)
              for (int64_t z = std::max<int64_t>(q0, 0); z <= std::min<int64_t>(q1, c.cols - 1); ++z) acc[i][y][z] = false;
          }
    e = torch::max_pool2d(v, 2, 2, 0, 1, true);
    var = torch::max_pool2d(var, 2, 2, 0, 1, true);
  }
  return mask;
}

void expect_close(const PressureTransferNet& net, const torch::Tensor& x, const torch::Tensor& ref,
                  const torch::Tensor& fast, const std::string& what) {
  ASSERT_EQ(ref.sizes(), fast.sizes()) << what;
  const float scale = std::max(1.0f, ref.abs().max().item<float>());
  const auto keep = flip_free_cells(net, x).unsqueeze(1).expand_as(ref);
  EXPECT_GT(keep.to(torch::kFloat).mean().item<float>(), 0.5f) << what << ": most cells compared";
  EXPECT_LE((ref - fast).abs().masked_select(keep).max().item<float>(), kFoldTolerance * scale) << what;
}

}  // namespace

TEST(ModelInference, FoldedEqualsModuleEveryArchitecture) {
  for (Arch arch : {Arch::faithful, Arch::skip, Arch::residual, Arch::frame}) {
    const ModelConfig c = small(arch);
    PressureTransferNet net = random_net(c);
    InferenceNet fast(net);
    auto x = torch::rand({3, c.window + 2 * input_margin(c), c.rows, c.cols});  // frame: its context too
    auto one = torch::randn({1, 3}).expand({3, 3}).contiguous();
    auto mixed = torch::randn({3, 3});
    auto other = torch::randn({3, 3});
    torch::NoGradGuard no_grad;
    expect_close(net, x, net->forward(x, one, one.flip(1)), fast.forward(x, one, one.flip(1)),
                 std::string(arch_name(arch)) + " one pair");
    expect_close(net, x, net->forward(x, mixed, other), fast.forward(x, mixed, other),
                 std::string(arch_name(arch)) + " mixed pairs");
    // Another pair after a cached one, then the first again.
    auto two = torch::randn({1, 3}).expand({3, 3}).contiguous();
    expect_close(net, x, net->forward(x, two, one), fast.forward(x, two, one), std::string(arch_name(arch)) + " new pair");
    expect_close(net, x, net->forward(x, one, one.flip(1)), fast.forward(x, one, one.flip(1)),
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
    expect_close(net, x, net->forward(x, a.expand({frames, 3}), a.flip(1).expand({frames, 3})),
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
    ModelConfig c = small(arch);
    c.channels[0] = 64;  // a wide first block: 19 windows make two chunks
    // No contact head: its output jumps at a logit of 0, and with 64 random
    // channels the logits' rounding (~1e-3) flips a cell now and then under
    // another instruction set (seen with ATEN_CPU_CAPABILITY=default).
    c.contact = false;
    ASSERT_EQ(chunk_windows(c, 19, kInferenceChunkBytes), 10) << arch_name(arch);
    PressureTransferNet net = random_net(c);
    InferenceNet fast(net);
    auto x = torch::rand({19, c.window + 2 * input_margin(c), c.rows, c.cols});  // 10 + 9 windows
    auto a = torch::randn({1, 3}).expand({19, 3});
    auto mixed = torch::randn({19, 3});
    torch::NoGradGuard no_grad;
    expect_close(net, x, net->forward(x, a, mixed), fast.forward(x, a, mixed), std::string(arch_name(arch)) + " batch 19");
    expect_close(net, x, net->forward(x, a, a), fast.forward(x, a, a), std::string(arch_name(arch)) + " batch 19, one pair");
  }
}

// A chunk's widest activation stays below the budget, and the chunks of a
// batch are equal: the paper's network runs 64 windows as two chunks of 32
// (36.7 MB in one), the 16/32/64 network and the fast preset's frame
// network in one.
TEST(ModelInference, ChunksKeepEveryTensorBelowTheBudget) {
  EXPECT_EQ(chunk_windows(ModelConfig::paper(), 64, kInferenceChunkBytes), 32);
  EXPECT_EQ(chunk_windows(ModelConfig::paper(), 73, kInferenceChunkBytes), 25);  // 36 fit: 25 + 25 + 23
  EXPECT_EQ(chunk_windows(ModelConfig::paper(), 1, kInferenceChunkBytes), 1);
  EXPECT_EQ(chunk_windows(ModelConfig::fast(), 64, kInferenceChunkBytes), 64);
  EXPECT_EQ(chunk_windows(TrainOptions::from_preset("fast").model, 64, kInferenceChunkBytes), 64);
  EXPECT_EQ(chunk_windows(TrainOptions::from_preset("fast").model, 1000, kInferenceChunkBytes), 143);  // 146 fit: 7 chunks
  ModelConfig skip = ModelConfig::paper();
  skip.arch = Arch::skip;  // the concatenation before the last layer: 128 channels at full resolution
  EXPECT_EQ(chunk_windows(skip, 64, kInferenceChunkBytes), 16);
  EXPECT_EQ(chunk_windows(ModelConfig::paper(), 64, 1), 1);  // a window larger than the budget: one at a time
}

// LibTorch reads a one-channel tensor whose strides are NCHW-contiguous as
// NCHW, although it is channels-last contiguous too (contiguous(ChannelsLast)
// keeps such strides); a convolution with such a kernel wrote NCHW, and the
// frame network's next layers ran on mixed layouts (its first pooling 5x
// slower). in_format gives the kernel channels-last strides.
TEST(ModelInference, OneChannelKernelsKeepTheChannelsLastLayout) {
  const auto cl = at::MemoryFormat::ChannelsLast;
  auto w = torch::randn({16, 1, 3, 3});
  auto x = torch::rand({16, 1, 80, 28}).contiguous(cl);
  torch::InferenceMode guard;
  ASSERT_FALSE(torch::conv2d(x, w.contiguous(cl), {}, 1, 1).is_contiguous(cl));  // the trap
  auto v = in_format(w, cl);
  EXPECT_TRUE(torch::equal(v, w));
  EXPECT_EQ(v.suggest_memory_format(), cl);
  EXPECT_TRUE(torch::conv2d(x, v, {}, 1, 1).is_contiguous(cl));
  EXPECT_TRUE(torch::conv2d(x.narrow(0, 0, 1), v, {}, 1, 1).is_contiguous(cl));  // batch 1 (no oneDNN)
}
