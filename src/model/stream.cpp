// Stream: causal sliding-window transfer, one frame at a time (stream.hpp).
//
// Dimension legend: K = window frames, H x W mat, A = 3 attributes.
// Buffers are allocated once: the window [1, K, H, W] (normalised, aligned
// input) is shifted by one frame per push; the attributes [1, A] are fixed,
// so the InferenceNet folds the body pair's FiLM once, at the first frame.
#include "ptnet/stream.hpp"

#include <cmath>
#include <cstring>

#include "model/loaded_model.hpp"
#include "ptnet/error.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

struct Stream::Impl {
  StreamOptions options;
  std::unique_ptr<LoadedModel> model;
  int k = 1, cells = 0;
  long long frames = 0;
  bool zoom = false;
  double scale = 1, gain = 1;
  PressureSequence one;           // one frame, for the alignment
  torch::Tensor window;           // [1, K, H, W] normalised input, oldest frame first
  torch::Tensor source, target;   // [1, A]
};

Stream::Stream(const std::string& model_dir, const BodySpec& source, const BodySpec& target,
               const StreamOptions& options)
    : impl_(std::make_unique<Impl>()) {
  check_body_range(source, "source body");
  check_body_range(target, "target body");
  Impl& s = *impl_;
  s.options = options;
  s.model = load_model(model_dir, "cpu", options.threads, /*batch=*/1);
  const ModelDir& d = s.model->dir;
  if (input_margin(d.model) > 0)
    throw Error::in(ModelFiles(model_dir).config(),
                    "the model reads frames ahead of each frame (context " + std::to_string(d.model.context) +
                        "); a stream transfers each frame as it arrives, so it needs a model with context 0");
  s.k = d.model.window;
  s.cells = d.model.rows * d.model.cols;
  s.zoom = d.model.align == Align::zoom;
  s.scale = body_scale(source.height_cm, target.height_cm);
  s.gain = body_gain(source.height_cm, source.weight_kg, target.height_cm, target.weight_kg);
  s.one = PressureSequence(d.mat, 1, d.fps);
  s.window = torch::zeros({1, s.k, d.model.rows, d.model.cols}, torch::kFloat32);
  auto sa = d.norm.attributes(source), ta = d.norm.attributes(target);
  s.source = torch::tensor(std::vector<float>(sa.begin(), sa.end())).view({1, kAttributes});
  s.target = torch::tensor(std::vector<float>(ta.begin(), ta.end())).view({1, kAttributes});
}

Stream::~Stream() = default;
Stream::Stream(Stream&&) noexcept = default;
Stream& Stream::operator=(Stream&&) noexcept = default;

const ModelDir& Stream::model() const { return impl_->model->dir; }
int Stream::frame_cells() const { return impl_->cells; }
int Stream::max_output_frames() const { return impl_->k; }
long long Stream::frames_in() const { return impl_->frames; }

int Stream::push(const float* frame, float* out) {
  Impl& s = *impl_;
  const ModelDir& d = s.model->dir;
  check_pressure(frame, std::size_t(s.cells), s.cells, s.options.input_name, "pressure frames", std::size_t(s.frames));
  std::memcpy(s.one.kpa.data(), frame, sizeof(float) * std::size_t(s.cells));
  const PressureSequence& in = s.zoom ? zoom_about_centre(s.one, s.scale, s.gain) : s.one;
  // Shift the window by one frame and append the new one, normalised.
  float* w = s.window.data_ptr<float>();
  if (s.k > 1) std::memmove(w, w + s.cells, sizeof(float) * std::size_t(s.cells) * std::size_t(s.k - 1));
  float* last = w + std::size_t(s.cells) * std::size_t(s.k - 1);
  const float inv = float(1.0 / d.norm.pressure_scale_kpa);
  for (int i = 0; i < s.cells; ++i) last[i] = in.kpa[std::size_t(i)] * inv;
  ++s.frames;
  if (s.frames < s.k) return 0;
  torch::InferenceMode inference;
  auto y = s.model->forward(s.window, s.source, s.target).contiguous();  // [1, K, H, W]
  const int ready = s.frames == s.k ? s.k : 1;  // the first window gives all its frames
  const float* src = y.data_ptr<float>() + std::size_t(s.cells) * std::size_t(s.k - ready);
  const float kpa = float(d.norm.pressure_scale_kpa);
  const double floor = s.options.raw ? 0.0 : d.norm.contact_threshold_kpa;  // as zero_below
  for (std::size_t i = 0; i < std::size_t(ready) * std::size_t(s.cells); ++i) {
    const float v = src[i] * kpa;
    out[i] = floor > 0 && v < floor ? 0.0f : v;
  }
  return ready;
}

}  // namespace ptnet
