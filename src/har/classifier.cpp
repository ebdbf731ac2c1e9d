// The small CNN activity classifier (ptnet/har.hpp). The only file of the
// har stage that includes LibTorch.
//
// Dimension legend: N windows, B time blocks (input channels), H x W pooled
// cells, C classes.
#include <ATen/CPUGeneratorImpl.h>
#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>
#include <random>

#include "har/har_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"

namespace ptnet::har {
namespace {

constexpr double kDropout = 0.2;     // before the last layer
constexpr int kPooledRows = 4;       // adaptive average pool output, along the mat
constexpr int kPooledCols = 2;       // ... and across

struct NetImpl : torch::nn::Module {
  NetImpl(int channels, int classes, const ClassifierOptions& o)
      : conv1(torch::nn::Conv2dOptions(channels, o.conv1, 3).padding(1)),
        bn1(o.conv1),
        conv2(torch::nn::Conv2dOptions(o.conv1, o.conv2, 3).padding(1)),
        bn2(o.conv2),
        pool(torch::nn::AdaptiveAvgPool2dOptions({kPooledRows, kPooledCols})),
        fc1(o.conv2 * kPooledRows * kPooledCols, o.hidden),
        fc2(o.hidden, classes) {
    register_module("conv1", conv1);
    register_module("bn1", bn1);
    register_module("conv2", conv2);
    register_module("bn2", bn2);
    register_module("pool", pool);
    register_module("fc1", fc1);
    register_module("fc2", fc2);
  }

  // x [N, B, H, W] -> logits [N, C]; dropout (training only) drawn from
  // `dropout`, the classifier's own generator, so that classifiers trained
  // at once on several threads stay deterministic.
  torch::Tensor forward(torch::Tensor x, at::Generator* dropout = nullptr) {
    x = torch::relu(bn1(conv1(x)));
    if (x.size(2) >= 2 && x.size(3) >= 2) x = torch::max_pool2d(x, 2);
    x = torch::relu(bn2(conv2(x)));
    if (x.size(2) >= 2 && x.size(3) >= 2) x = torch::max_pool2d(x, 2);
    x = pool(x).flatten(1);
    x = torch::relu(fc1(x));
    if (is_training() && dropout) {
      const torch::Tensor keep =
          at::bernoulli(torch::full(x.sizes(), 1 - kDropout, torch::kFloat32), *dropout).to(x.device());
      x = x * keep / (1 - kDropout);
    }
    return fc2(x);
  }

  torch::nn::Conv2d conv1;
  torch::nn::BatchNorm2d bn1;
  torch::nn::Conv2d conv2;
  torch::nn::BatchNorm2d bn2;
  torch::nn::AdaptiveAvgPool2d pool;
  torch::nn::Linear fc1;
  torch::nn::Linear fc2;
};
TORCH_MODULE(Net);

torch::Device parse_device(const std::string& name) {
  try {
    torch::Device d(name);
    if (d.is_cuda() && !torch::cuda::is_available())
      throw Error("har: device " + name + " requested but CUDA is not available");
    return d;
  } catch (const c10::Error&) {
    throw Error("har: unknown device '" + name + "' (expected cpu, cuda or cuda:N)");
  }
}

}  // namespace

struct WindowClassifier::Impl {
  int channels, rows, cols, classes;
  ClassifierOptions options;
  torch::Device device;
  Net net;
  float mean = 0, scale = 1;  // input standardisation from the training set

  at::Generator dropout;

  Impl(int ch, int r, int c, int k, const ClassifierOptions& o)
      : channels(ch), rows(r), cols(c), classes(k), options(o), device(parse_device(o.device)),
        net(nullptr), dropout(at::make_generator<at::CPUGeneratorImpl>(o.seed)) {
    // The initial weights come from LibTorch's global generator: seeded and
    // drawn under one lock, the same whichever thread builds the classifier.
    static std::mutex init;
    const std::lock_guard<std::mutex> lock(init);
    use_threads();
    torch::manual_seed(o.seed);
    net = Net(ch, k, o);
    net->to(device);
  }

  // LibTorch's CPU threads for the calling thread (OpenMP keeps the count per thread).
  void use_threads() const {
    if (options.threads > 0) torch::set_num_threads(options.threads);
  }

  void check(const PreparedWindows& in) const {
    if (in.channels != channels || in.rows != rows || in.cols != cols)
      throw Error("har: classifier expects windows of " + std::to_string(channels) + "x" +
                  std::to_string(rows) + "x" + std::to_string(cols) + ", found " +
                  std::to_string(in.channels) + "x" + std::to_string(in.rows) + "x" +
                  std::to_string(in.cols));
  }

  // [N, B, H, W] float tensor on the CPU viewing `in` (no copy).
  torch::Tensor view(const PreparedWindows& in) const {
    return torch::from_blob(const_cast<float*>(in.values.data()),
                            {in.count(), channels, rows, cols}, torch::kFloat32);
  }
};

WindowClassifier::WindowClassifier(int channels, int rows, int cols, int classes,
                                   const ClassifierOptions& options) {
  if (channels < 1 || rows < 1 || cols < 1)
    throw Error("har: classifier input must be non-empty, found " + std::to_string(channels) +
                "x" + std::to_string(rows) + "x" + std::to_string(cols));
  if (classes < 2) throw Error("har: a classifier needs at least 2 classes, found " +
                               std::to_string(classes));
  if (options.epochs < 1 || options.batch_size < 1 || !(options.learning_rate > 0))
    throw Error("har: epochs, batch size and learning rate must be positive");
  impl_ = std::make_unique<Impl>(channels, rows, cols, classes, options);
}

WindowClassifier::~WindowClassifier() = default;
WindowClassifier::WindowClassifier(WindowClassifier&&) noexcept = default;
WindowClassifier& WindowClassifier::operator=(WindowClassifier&&) noexcept = default;

double WindowClassifier::train(const PreparedWindows& inputs, const std::vector<int>& labels) {
  Impl& m = *impl_;
  m.check(inputs);
  const int n = inputs.count();
  if (n < 1) throw Error("har: no training windows");
  if (int(labels.size()) != n)
    throw Error("har: " + std::to_string(n) + " training windows but " +
                std::to_string(labels.size()) + " labels");
  for (int l : labels)
    if (l < 0 || l >= m.classes)
      throw Error("har: label " + std::to_string(l) + " outside 0.." + std::to_string(m.classes - 1));

  m.use_threads();
  m.dropout.set_current_seed(m.options.seed);
  torch::Tensor x = m.view(inputs);
  {
    torch::NoGradGuard g;
    m.mean = x.mean().item<float>();
    m.scale = std::max(1e-6f, x.std().item<float>());
  }
  torch::Tensor y = torch::from_blob(const_cast<int*>(labels.data()), {n}, torch::kInt32)
                        .to(torch::kInt64);
  torch::Tensor weight;  // undefined: unweighted
  if (m.options.balanced) {
    std::vector<float> count(std::size_t(m.classes), 0.0f);
    for (int l : labels) count[std::size_t(l)] += 1;
    std::vector<float> w(count.size(), 0.0f);
    for (std::size_t c = 0; c < count.size(); ++c) w[c] = count[c] > 0 ? float(n) / (m.classes * count[c]) : 0.0f;
    weight = torch::tensor(w).to(m.device);
  }
  torch::optim::Adam opt(m.net->parameters(), torch::optim::AdamOptions(m.options.learning_rate)
                                                  .weight_decay(m.options.weight_decay));
  std::mt19937_64 rng(m.options.seed);
  std::vector<int64_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  const int batch = std::min(m.options.batch_size, n);
  double last = 0;
  m.net->train();
  for (int epoch = 0; epoch < m.options.epochs; ++epoch) {
    if (m.options.cosine) {
      const double lr = m.options.learning_rate * 0.5 * (1 + std::cos(M_PI * epoch / m.options.epochs));
      for (auto& group : opt.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
    }
    std::shuffle(order.begin(), order.end(), rng);
    double total = 0;
    int steps = 0;
    for (int start = 0; start < n; start += batch) {
      const int count = std::min(batch, n - start);
      if (count < 2 && n >= 2) continue;  // BatchNorm needs 2+ windows per batch
      torch::Tensor idx = torch::from_blob(order.data() + start, {count}, torch::kInt64);
      torch::Tensor xb = ((x.index_select(0, idx) - m.mean) / m.scale).to(m.device);
      torch::Tensor yb = y.index_select(0, idx).to(m.device);
      opt.zero_grad();
      torch::Tensor loss = torch::nn::functional::cross_entropy(
          m.net->forward(xb, &m.dropout), yb, torch::nn::functional::CrossEntropyFuncOptions().weight(weight));
      loss.backward();
      opt.step();
      total += loss.item<double>();
      ++steps;
    }
    last = steps ? total / steps : 0.0;
  }
  m.net->eval();
  return last;
}

std::vector<float> WindowClassifier::probabilities(const PreparedWindows& inputs) const {
  Impl& m = *impl_;
  m.check(inputs);
  const int n = inputs.count();
  std::vector<float> out(std::size_t(n) * std::size_t(m.classes), 0.0f);
  if (n == 0) return out;
  torch::NoGradGuard g;
  m.use_threads();
  m.net->eval();
  torch::Tensor x = m.view(inputs);
  constexpr int kChunk = 512;  // windows per forward pass
  for (int start = 0; start < n; start += kChunk) {
    const int count = std::min(kChunk, n - start);
    torch::Tensor xb = ((x.narrow(0, start, count) - m.mean) / m.scale).to(m.device);
    torch::Tensor p = torch::softmax(m.net->forward(xb), 1).to(torch::kCPU).contiguous();
    std::copy(p.data_ptr<float>(), p.data_ptr<float>() + p.numel(),
              out.begin() + std::ptrdiff_t(start) * m.classes);
  }
  return out;
}

std::vector<int> WindowClassifier::predict(const PreparedWindows& inputs) const {
  return argmax_rows(probabilities(inputs), impl_->classes);
}

}  // namespace ptnet::har
