// PressureTransferNet: shapes, parameter count, non-negative output, one
// optimiser step lowers the loss, weights round-trip, config validation.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/model_config_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model.hpp"

using namespace ptnet;

namespace {

ModelConfig small(Arch arch = Arch::faithful) {
  ModelConfig c;
  c.arch = arch;
  c.channels = {4, 8, 8};
  c.hidden = 16;
  c.latent = 16;
  return c;
}

}  // namespace

TEST(ModelNet, PooledSizesHalveWithCeiling) {
  ModelConfig c;
  EXPECT_EQ(pooled_size(c, 1), (std::array<int, 2>{40, 14}));
  EXPECT_EQ(pooled_size(c, 2), (std::array<int, 2>{20, 7}));
  EXPECT_EQ(pooled_size(c, 3), (std::array<int, 2>{10, 4}));
}

TEST(ModelNet, OutputShapeAndNonNegativeEveryArchitecture) {
  torch::manual_seed(0);
  for (Arch arch : {Arch::faithful, Arch::skip, Arch::residual, Arch::frame}) {
    PressureTransferNet net(small(arch));
    auto x = torch::rand({3, 30, 80, 28});
    auto a = torch::randn({3, 3});
    auto y = net->forward(x, a, a.flip(0));
    EXPECT_EQ(y.sizes(), (std::vector<int64_t>{3, 30, 80, 28})) << arch_name(arch);
    EXPECT_GE(y.min().item<float>(), 0.0f);
  }
}

TEST(ModelNet, ParameterCountMatchesClosedForm) {
  for (Arch arch : {Arch::faithful, Arch::skip, Arch::residual, Arch::frame}) {
    ModelConfig c = small(arch);
    PressureTransferNet net(c);
    EXPECT_EQ(parameter_count(*net), parameter_count(c)) << arch_name(arch);
  }
  ModelConfig with_context = small(Arch::frame);
  with_context.context = 2;
  EXPECT_EQ(parameter_count(*PressureTransferNet(with_context)), parameter_count(with_context));
  with_context.contact = true;
  EXPECT_EQ(parameter_count(*PressureTransferNet(with_context)), parameter_count(with_context));
  // The paper's widths (64/128/256, 128, 128): 30x64x9+64 + ... (see model_config.cpp).
  ModelConfig paper = ModelConfig::paper();
  PressureTransferNet net(paper);
  EXPECT_EQ(parameter_count(*net), parameter_count(paper));
  EXPECT_EQ(parameter_count(paper), 3453214);  // 3.45 M
}

TEST(ModelNet, OddMatSizesRoundTrip) {
  ModelConfig c = small();
  c.rows = 21;
  c.cols = 9;
  c.window = 5;
  PressureTransferNet net(c);
  auto y = net->forward(torch::rand({2, 5, 21, 9}), torch::zeros({2, 3}), torch::zeros({2, 3}));
  EXPECT_EQ(y.sizes(), (std::vector<int64_t>{2, 5, 21, 9}));
}

TEST(ModelNet, WrongInputShapeIsAClearError) {
  PressureTransferNet net(small());
  try {
    net->forward(torch::rand({2, 30, 64, 28}), torch::zeros({2, 3}), torch::zeros({2, 3}));
    FAIL() << "no error";
  } catch (const c10::Error& e) {
    EXPECT_NE(std::string(e.what_without_backtrace()).find("expected input [N, 30, 80, 28]"), std::string::npos);
  }
}

TEST(ModelNet, OneAdamStepLowersTheLossOnAFixedBatch) {
  torch::manual_seed(1);
  for (Arch arch : {Arch::faithful, Arch::skip, Arch::residual, Arch::frame}) {
    PressureTransferNet net(small(arch));
    net->train();
    auto x = torch::rand({8, 30, 80, 28});
    auto target = x * 1.5;
    auto sa = torch::zeros({8, 3}), ta = torch::ones({8, 3});
    torch::optim::Adam opt(net->parameters(), torch::optim::AdamOptions(1e-3));
    auto before = torch::mse_loss(net->forward(x, sa, ta), target);
    opt.zero_grad();
    before.backward();
    opt.step();
    auto after = torch::mse_loss(net->forward(x, sa, ta), target);
    EXPECT_LT(after.item<double>(), before.item<double>()) << arch_name(arch);
  }
}

TEST(ModelNet, WeightsRoundTripAndMismatchIsAClearError) {
  auto dir = std::filesystem::temp_directory_path() / ("ptnet_model_net_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "w.pt").string();
  torch::manual_seed(2);
  PressureTransferNet a(small());
  save_weights(a, path);
  torch::manual_seed(3);
  PressureTransferNet b(small());
  load_weights(b, path);
  for (const auto& p : a->named_parameters())
    EXPECT_TRUE(torch::equal(p.value(), b->named_parameters()[p.key()])) << p.key();

  ModelConfig wide = small();
  wide.channels = {6, 8, 8};
  PressureTransferNet c(wide);
  try {
    load_weights(c, path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("conv1.weight\" has shape [4, 30, 3, 3], the model expects [6, 30, 3, 3]"),
              std::string::npos)
        << e.what();
  }
  std::ofstream(path) << "garbage";
  EXPECT_THROW(load_weights(b, path), Error);
  std::filesystem::remove_all(dir);
}

TEST(ModelNet, ConfigValidation) {
  ModelConfig c;
  c.channels = {0, 8, 8};
  try {
    validate(c);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "model: channels must be in 1-4096, found 0");
  }
  EXPECT_THROW(parse_arch("unet"), Error);
  EXPECT_EQ(parse_arch("skip"), Arch::skip);
  EXPECT_EQ(parse_arch("residual"), Arch::residual);
  EXPECT_EQ(model_config_from_json(to_json(small(Arch::residual)), "config.json").arch, Arch::residual);
  ModelConfig f = small(Arch::frame);
  f.context = 3;
  f.window = 1;
  f.contact = true;
  const ModelConfig back = model_config_from_json(to_json(f), "config.json");
  EXPECT_EQ(back.arch, Arch::frame);
  EXPECT_EQ(back.context, 3);
  EXPECT_EQ(back.window, 1);
  EXPECT_TRUE(back.contact);
  auto no_head = to_json(f);
  no_head.erase("contact");  // config.json of a model from before the contact head
  EXPECT_FALSE(model_config_from_json(no_head, "config.json").contact);
  no_head["contact"] = 1;
  EXPECT_THROW(model_config_from_json(no_head, "config.json"), Error);
  f.context = -1;
  EXPECT_THROW(validate(f), Error);
}

TEST(ModelNet, FrameArchIsPerFrameAndStartsAsItsInput) {
  // Untrained, the frame network is its input (zero-initialised head and FiLM).
  // Its input window carries `context` frames beyond each end: 5 frames in,
  // 3 out. Its output for a frame depends only on that frame and its context:
  // the same frame in two windows of different lengths gives the same output;
  // after training steps the target attributes change the output, and so do
  // the context frames (the network reads its neighbours).
  torch::manual_seed(4);
  ModelConfig c = small(Arch::frame);
  c.window = 3;
  c.context = 1;
  ASSERT_EQ(input_margin(c), 1);
  PressureTransferNet net(c);
  auto x = torch::rand({2, 5, 80, 28});
  auto a = torch::randn({2, 3});
  {
    net->eval();
    torch::NoGradGuard no_grad;
    auto y = net->forward(x, a, a.flip(0));
    ASSERT_EQ(y.sizes(), (std::vector<int64_t>{2, 3, 80, 28}));
    EXPECT_EQ((y - x.narrow(1, 1, 3)).abs().max().item<float>(), 0.0f);
  }
  // Truth that needs the context: each frame plus its next neighbour.
  auto truth = x.narrow(1, 1, 3) + 0.5 * x.narrow(1, 2, 3);
  net->train();
  torch::optim::Adam opt(net->parameters(), torch::optim::AdamOptions(1e-2));
  for (int i = 0; i < 5; ++i) {
    opt.zero_grad();
    auto loss = torch::mse_loss(net->forward(x, a, a.flip(0)), truth * (1 + a.flip(0).select(1, 2).view({2, 1, 1, 1})));
    loss.backward();
    opt.step();
  }
  net->eval();
  torch::NoGradGuard no_grad;
  auto y = net->forward(x, a, a.flip(0));
  EXPECT_GT((y - net->forward(x, a, a)).abs().max().item<float>(), 1e-4f);  // target attributes matter
  auto later = x.clone();
  later.narrow(1, 4, 1).mul_(3.0);  // only frame 4: the context of output frame 2
  auto moved = net->forward(later, a, a.flip(0));
  EXPECT_GT((moved.narrow(1, 2, 1) - y.narrow(1, 2, 1)).abs().max().item<float>(), 1e-4f);  // it reads its context
  EXPECT_EQ((moved.narrow(1, 0, 2) - y.narrow(1, 0, 2)).abs().max().item<float>(), 0.0f);  // and nothing else
  // Output frame 1 (input frame 2) from a window of one: frames 1..3 in.
  ModelConfig c1 = c;
  c1.window = 1;
  PressureTransferNet n1(c1);
  torch::serialize::OutputArchive ar;
  write_weights(net, ar);
  std::stringstream buf;
  ar.save_to(buf);
  torch::serialize::InputArchive in;
  in.load_from(buf);
  read_weights(n1, in, "memory");
  n1->eval();
  auto middle = n1->forward_raw(x.narrow(1, 1, 3), a, a.flip(0));
  EXPECT_LT((middle - net->forward_raw(x, a, a.flip(0)).narrow(1, 1, 1)).abs().max().item<float>(), 1e-5f);
  EXPECT_THROW(net->forward(x.narrow(1, 0, 2), a, a), c10::Error);  // 2 frames: none inside a context of 1
}

TEST(ModelNet, ContactHeadZeroesCellsOutOfContactAndLiftsTheRest) {
  // The output of a contact-head model is 0 where the contact logit is < 0
  // and at least the floor where it is > 0; the pressure channel is the same
  // as without the head. Untrained, the logit is -2 everywhere: no contact.
  torch::manual_seed(5);
  ModelConfig c = small(Arch::frame);
  c.window = 2;
  c.contact = true;
  PressureTransferNet net(c);
  net->set_contact_floor(0.25);
  net->eval();
  torch::NoGradGuard no_grad;
  auto x = torch::rand({2, 2, 80, 28});
  auto a = torch::randn({2, 3});
  auto raw = net->forward_parts(x, a, a.flip(0));
  ASSERT_TRUE(raw.contact.defined());
  EXPECT_EQ(raw.contact.sizes(), x.sizes());
  EXPECT_EQ(net->forward(x, a, a.flip(0)).abs().max().item<float>(), 0.0f);  // no contact yet
  // Contact where the input is above 0.5: there the output is max(x, 0.25).
  raw.contact = (x > 0.5).to(torch::kFloat) * 2 - 1;
  auto y = net->contact_output(raw);
  EXPECT_EQ(y.masked_select(x <= 0.5).abs().max().item<float>(), 0.0f);
  EXPECT_LT((y - torch::where(x > 0.5, x.clamp_min(0.25), torch::zeros_like(x))).abs().max().item<float>(), 1e-6f);
  // The floor is a buffer: it travels with the weights.
  std::stringstream buf;
  {
    torch::serialize::OutputArchive ar;
    write_weights(net, ar);
    ar.save_to(buf);
  }
  PressureTransferNet copy(c);
  torch::serialize::InputArchive in;
  in.load_from(buf);
  read_weights(copy, in, "memory");
  copy->eval();
  EXPECT_EQ((copy->contact_output(raw) - y).abs().max().item<float>(), 0.0f);
  // Only the frame network has a contact head.
  ModelConfig bad = small(Arch::residual);
  bad.contact = true;
  EXPECT_THROW(validate(bad), Error);
}

TEST(ModelNet, ResidualWithAZeroDecoderCopiesTheSource) {
  // output = ReLU(input + decoder): with the last layer zeroed the network is
  // the copy baseline, whatever the attributes; the other architectures are not.
  torch::manual_seed(3);
  auto x = torch::rand({2, 30, 80, 28});
  auto a = torch::randn({2, 3});
  for (Arch arch : {Arch::residual, Arch::skip}) {
    PressureTransferNet net(small(arch));
    net->eval();
    torch::NoGradGuard no_grad;
    for (auto& item : net->named_parameters())
      if (item.key().rfind("deconv1.", 0) == 0) item.value().zero_();
    const float diff = (net->forward(x, a, a.flip(0)) - x).abs().max().item<float>();
    if (arch == Arch::residual) EXPECT_EQ(diff, 0.0f);
    else EXPECT_GT(diff, 0.1f);
  }
}

TEST(ModelNet, FlopsOfThePaperNetwork) {
  // Encoder convs at 80x28, 40x14, 20x7 + decoder mirror + FCs, x2 for MACs.
  const double f = forward_flops(ModelConfig::paper());
  EXPECT_NEAR(f / 1e9, 0.490468, 1e-5);  // GFLOP per window
}
