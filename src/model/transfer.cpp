// Whole-sequence transfer with overlapping windows (Torch).
//
// Dimension legend: T frames of the sequence, K = window frames, H x W mat.
#include "ptnet/transfer.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/rate.hpp"
#include "model/model_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "model/loaded_model.hpp"

namespace ptnet {

std::unique_ptr<LoadedModel> load_model(const std::string& model_dir, const std::string& device, int threads,
                                        int batch) {
  if (threads < 0 || threads > max_threads())
    throw Error("transfer: threads must be in 0-" + std::to_string(max_threads()) + ", found " +
                std::to_string(threads));
  const ModelFiles files(model_dir);
  const std::string config_path = files.config(), weights_path = files.weights();
  note_input(config_path);  // no output of this run may replace the model
  note_input(weights_path);
  auto m = std::make_unique<LoadedModel>();
  m->dir = read_model_dir(model_dir);
  m->device = parse_device(device);
  if (threads > 0) torch::set_num_threads(threads);
  check_memory(model_memory_bytes(m->dir.model, batch, /*training=*/false), config_path,
               "the model (" + std::to_string(parameter_count(m->dir.model)) + " parameters)");
  m->net = PressureTransferNet(m->dir.model);
  load_weights(m->net, weights_path);
  check_weights_digest(*m->net, recorded_digest(m->dir, ModelFiles::kWeights), weights_path, config_path);
  m->net->eval();
  if (m->device.is_cpu()) m->fast = std::make_unique<InferenceNet>(m->net);
  m->net->to(m->device);
  return m;
}

torch::Tensor LoadedModel::forward(const torch::Tensor& x, const torch::Tensor& source, const torch::Tensor& target) {
  const auto once = [&](const torch::Tensor& in) {
    if (fast) return fast->forward(in, source, target);
    return net->forward(in.to(device), source.to(device), target.to(device)).cpu();
  };
  std::unique_lock<std::mutex> lock(mutex, std::defer_lock);
  if (fast) lock.lock();
  torch::NoGradGuard no_grad;
  return dir.model.mirror ? mirror_averaged(once, x) : once(x);
}

struct Transfer::Impl {
  TransferOptions options;
  std::unique_ptr<LoadedModel> model;
};

Transfer::Transfer(const std::string& model_dir, const TransferOptions& options)
    : impl_(std::make_unique<Impl>()) {
  check_range("stride", options.stride, kTransferOptionsRanges.stride);
  check_range("batch", options.batch, kTransferOptionsRanges.batch);
  impl_->options = options;
  impl_->model = load_model(model_dir, options.device, options.threads, options.batch);
}

Transfer::~Transfer() = default;
Transfer::Transfer(Transfer&&) noexcept = default;
Transfer& Transfer::operator=(Transfer&&) noexcept = default;

const ModelDir& Transfer::model() const { return impl_->model->dir; }

PressureSequence Transfer::run(const PressureSequence& src, const BodySpec& source,
                               const BodySpec& target) const {
  const ModelDir& d = impl_->model->dir;
  const int k = d.model.window, h = d.model.rows, w = d.model.cols;
  if (src.mat.rows != h || src.mat.cols != w)
    throw Error::in(d.path, "model is built for a " + std::to_string(h) + " x " + std::to_string(w) +
                                " mat, the sequence has " + std::to_string(src.mat.rows) + " x " +
                                std::to_string(src.mat.cols));
  if (!same_rate(src.fps, d.fps))
    throw Error::in(d.path, "model is trained at " + number_text(d.fps) +
                                " fps, the sequence is at " + number_text(src.fps) +
                                " fps (simulate the data again with " + field_text("fps") + " " +
                                number_text(d.fps) + ")");
  const int t = src.frames();
  if (t < k)
    throw Error("transfer: sequence has " + std::to_string(t) + " frames, the model's window needs at least " +
                std::to_string(k));
  check_body_range(source, "source body");
  check_body_range(target, "target body");
  // Readings a mat cannot make (3e38 kPa became zeros, negative kPa passed).
  check_pressure(src.kpa.data(), src.kpa.size(), h * w, "transfer", "the source sequence");

  // Window starts every `stride` frames, plus one ending at the last frame.
  // (A stride beyond the window would leave frames uncovered.)
  const int stride = std::min(impl_->options.stride, k);
  std::vector<int> starts;
  for (int s = 0; s + k <= t; s += stride) starts.push_back(s);
  if (starts.back() != t - k) starts.push_back(t - k);

  const float inv_scale = float(1.0 / d.norm.pressure_scale_kpa);
  auto sa = d.norm.attributes(source), ta = d.norm.attributes(target);
  // The network's input: the sequence itself, or aligned to the target body.
  const PressureSequence aligned =
      d.model.align == Align::zoom
          ? zoom_about_centre(src, body_scale(source.height_cm, target.height_cm),
                              body_gain(source.height_cm, source.weight_kg, target.height_cm, target.weight_kg))
          : PressureSequence{};
  const PressureSequence& in = d.model.align == Align::zoom ? aligned : src;
  torch::InferenceMode inference;
  // Window s's input is input[s, s + K + 2m): its frames and their context.
  const int m = input_margin(d.model);
  torch::Tensor input = with_margin(
      torch::from_blob(const_cast<float*>(in.kpa.data()), {t, h, w}, torch::kFloat32).mul(inv_scale), m);  // [T+2m,H,W]
  PressureSequence out(src.mat, t, src.fps);
  torch::Tensor sum = torch::from_blob(out.kpa.data(), {t, h, w}, torch::kFloat32);  // [T, H, W], out's memory
  sum.zero_();
  torch::Tensor cover = torch::zeros({t}, torch::kFloat32);              // windows per frame
  const int batch = impl_->options.batch;
  const auto s_all = torch::tensor(std::vector<float>(sa.begin(), sa.end())).view({1, 3});
  const auto t_all = torch::tensor(std::vector<float>(ta.begin(), ta.end())).view({1, 3});
  for (std::size_t b = 0; b < starts.size(); b += batch) {
    const int n = int(std::min<std::size_t>(batch, starts.size() - b));
    // Consecutive windows of one frame (the frame network) are a view, else a stack.
    torch::Tensor x;
    if (k == 1 && starts[b + n - 1] - starts[b] == n - 1) {
      x = input.narrow(0, starts[b], n + 2 * m).unfold(0, 1 + 2 * m, 1).permute({0, 3, 1, 2});  // [n,1+2m,H,W]
    } else {
      std::vector<torch::Tensor> windows;
      for (int i = 0; i < n; ++i) windows.push_back(input.narrow(0, starts[b + i], k + 2 * m));
      x = torch::stack(windows);                                          // [n, K + 2m, H, W]
    }
    auto y = impl_->model->forward(x, s_all.expand({n, 3}), t_all.expand({n, 3}));  // [n, K, H, W]
    for (int i = 0; i < n; ++i) {
      sum.narrow(0, starts[b + i], k).add_(y[i]);
      cover.narrow(0, starts[b + i], k).add_(1.0f);
    }
  }
  sum.div_(cover.view({t, 1, 1})).mul_(float(d.norm.pressure_scale_kpa));
  if (!impl_->options.raw && d.norm.contact_threshold_kpa > 0) zero_below(out, d.norm.contact_threshold_kpa);
  return out;
}

}  // namespace ptnet
