// Windows as tensors, and the training augmentations (batcher.hpp).
#include "batcher.hpp"

#include <algorithm>
#include <cmath>

namespace ptnet {

void Batcher::read_with_margin(int seq, int start, int count, float* out) {
  if (margin_ == 0) return cache_.read(seq, start, count, out);
  const int last = source_.sequences()[std::size_t(seq)].frames - 1;
  const std::size_t cells = std::size_t(source_.mat().cells());
  for (int f = start - margin_; f < start + count + margin_; ++f, out += cells)  // as with_margin: ends repeated
    cache_.read(seq, std::clamp(f, 0, last), 1, out);
}

Batch Batcher::load(const std::vector<WindowRef>& refs, bool with_source) {
  const int n = int(refs.size()), t = index_.options().window, ti = t + 2 * margin_;
  const MatSpec m = source_.mat();
  const std::int64_t per = std::int64_t(t) * m.cells(), per_in = std::int64_t(ti) * m.cells();
  Batch b;
  b.margin = margin_;
  b.x = torch::empty({n, ti, m.rows, m.cols}, torch::kFloat32);
  b.y = torch::empty({n, t, m.rows, m.cols}, torch::kFloat32);
  b.sa = torch::empty({n, kAttributes}, torch::kFloat32);
  b.ta = torch::empty({n, kAttributes}, torch::kFloat32);
  float *x = b.x.data_ptr<float>(), *y = b.y.data_ptr<float>();
  float *sa = b.sa.data_ptr<float>(), *ta = b.ta.data_ptr<float>();
  // Aligned input: the recorded source windows (with their margin) go to a
  // scratch window, their zoom to b.x, and their centre frames to b.src
  // (kept for the baselines).
  const bool aligned = align_ == Align::zoom;
  if (aligned && with_source) b.src = torch::empty_like(b.y);
  std::vector<float> scratch(aligned ? std::size_t(per_in) : 0);
  for (int i = 0; i < n; ++i) {
    const Pair& p = index_.pairs()[std::size_t(refs[i].pair)];
    if (aligned) {
      read_with_margin(p.source, refs[i].start, t, scratch.data());
      if (with_source)
        std::copy_n(scratch.data() + std::size_t(margin_) * m.cells(), per, b.src.data_ptr<float>() + i * per);
      const BodySpec& a = body_of(p.source);
      const BodySpec& z = body_of(p.target);
      zoom_frames(scratch.data(), x + i * per_in, ti, m.rows, m.cols, body_scale(a.height_cm, z.height_cm),
                  body_gain(a.height_cm, a.weight_kg, z.height_cm, z.weight_kg));
    } else {
      read_with_margin(p.source, refs[i].start, t, x + i * per_in);
    }
    cache_.read(p.target, refs[i].start, t, y + i * per);
    std::copy_n(attrs_[std::size_t(p.source)].data(), kAttributes, sa + i * kAttributes);
    std::copy_n(attrs_[std::size_t(p.target)].data(), kAttributes, ta + i * kAttributes);
  }
  b.x.mul_(inv_scale_);
  b.y.mul_(inv_scale_);
  if (aligned && with_source) b.src.mul_(inv_scale_);
  else b.src = b.centre();
  if (device_ != torch::kCPU) {
    b.x = b.x.to(device_), b.y = b.y.to(device_), b.sa = b.sa.to(device_), b.ta = b.ta.to(device_);
    b.src = b.src.to(device_);
  }
  return b;
}

void crop_to_pressure(Batch& b, int rows) {
  const auto n = b.x.size(0), h = b.x.size(2);
  if (rows >= h) return;
  auto profile = (b.centre() + b.y).sum({1, 3});                            // [N,H]
  auto mass = profile.sum(1);                                               // [N]
  auto centre = (profile * torch::arange(h, profile.options())).sum(1) / mass.clamp_min(1e-12);
  const torch::Tensor centre_cpu = centre.cpu(), mass_cpu = mass.cpu();
  const auto centres = centre_cpu.accessor<float, 1>();
  const auto masses = mass_cpu.accessor<float, 1>();
  std::vector<torch::Tensor> xs, ys;
  for (int64_t i = 0; i < n; ++i) {
    const double c = masses[i] > 0 ? double(centres[i]) : 0.5 * double(h);
    const int64_t r0 = std::clamp<int64_t>(std::llround(c - 0.5 * rows), 0, h - rows);
    xs.push_back(b.x[i].narrow(1, r0, rows));
    ys.push_back(b.y[i].narrow(1, r0, rows));
  }
  b.x = torch::stack(xs);
  b.y = torch::stack(ys);
}

void mirror_every_second(Batch& b) {
  using torch::indexing::None;
  using torch::indexing::Slice;
  const auto odd = Slice(1, None, 2);
  for (torch::Tensor* t : {&b.x, &b.y}) {
    torch::Tensor out = t->clone();
    out.index_put_({odd}, t->index({odd}).flip({-1}));
    *t = out;
  }
}

}  // namespace ptnet
