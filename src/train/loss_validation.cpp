// The training loss and the validation pass (loss_validation.hpp).
#include "loss_validation.hpp"

#include <algorithm>
#include <cmath>

namespace ptnet {

torch::Tensor training_loss(const TrainOptions& o, const PressureTransferNetImpl::Raw& raw,
                            const torch::Tensor& truth) {
  auto out = torch::where(truth > 0, raw.pressure, torch::relu(raw.pressure));
  auto loss = torch::mse_loss(out, truth);
  if (o.loss == Loss::mse_force) {
    // Relative error of the total force of each frame, squared.
    auto f_out = out.sum({2, 3}), f_truth = truth.sum({2, 3});
    loss = loss + o.force_weight * ((f_out - f_truth) / (f_truth + 1.0)).pow(2).mean();
  }
  if (raw.contact.defined())
    loss = loss + o.contact_weight * torch::binary_cross_entropy_with_logits(raw.contact, (truth > 0).to(raw.contact.dtype()));
  return loss;
}

ValidationResult validate_model(PressureTransferNet& net, Batcher& batcher, const WindowIndex& index,
                                const TrainOptions& o, double scale_kpa, bool baselines, Communicator& comm,
                                bool mirrored) {
  const std::int64_t total = index.val_size();
  const std::int64_t n = o.val_samples > 0 ? std::min(o.val_samples, total) : total;
  net->eval();
  torch::NoGradGuard no_grad;
  double sum = 0, copy_sum = 0, scale_sum = 0, zero_sum = 0, zoom_sum = 0;
  const bool aligned = net->config().align == Align::zoom;
  double ones = 0, copy_mismatches = 0;
  std::vector<double> mismatches(kCandidates, 0.0);
  std::int64_t count = 0;
  std::vector<WindowRef> refs;
  std::int64_t chunk = 0;  // micro-batches so far
  auto flush = [&]() {
    if (refs.empty()) return;
    if (chunk++ % comm.size() != comm.rank()) {
      refs.clear();
      return;
    }
    Batch b = batcher.load(refs, baselines);
    const auto forward = [&](const torch::Tensor& x) { return net->forward(x, b.sa, b.ta); };
    auto out = mirrored ? mirror_averaged(forward, b.x) : forward(b.x);
    sum += torch::mse_loss(out, b.y, torch::Reduction::Sum).item<double>();
    if (baselines) {
      copy_sum += torch::mse_loss(b.src, b.y, torch::Reduction::Sum).item<double>();
      zero_sum += b.y.pow(2).sum().item<double>();
      if (aligned) zoom_sum += torch::mse_loss(b.centre(), b.y, torch::Reduction::Sum).item<double>();
      std::vector<float> ratio;
      for (const auto& r : refs) ratio.push_back(float(batcher.weight_ratio(r)));
      auto k = torch::tensor(ratio).view({-1, 1, 1, 1}).to(b.x.device());
      scale_sum += torch::mse_loss(b.src * k, b.y, torch::Reduction::Sum).item<double>();
      const auto contact = b.y * float(scale_kpa) > kContactKpa;     // [N,T,H,W] bool
      const auto out_kpa = out * float(scale_kpa);
      ones += contact.sum().item<double>();
      copy_mismatches += ((b.src * float(scale_kpa) > kContactKpa) != contact).sum().item<double>();
      for (int c = 0; c < kCandidates; ++c) {
        const double t = std::max(kThresholdCandidatesKpa[c], kContactKpa);
        mismatches[std::size_t(c)] += ((out_kpa >= t) != contact).sum().item<double>();
      }
    }
    count += out.numel();
    refs.clear();
  };
  for (std::int64_t i = 0; i < n; ++i) {
    refs.push_back(index.val(n == total ? i : i * total / n));
    if (int(refs.size()) == std::min(o.batch, o.micro_batch)) flush();
  }
  flush();
  std::vector<double> sums{sum, copy_sum, scale_sum, zero_sum, zoom_sum, ones, copy_mismatches, double(count)};
  sums.insert(sums.end(), mismatches.begin(), mismatches.end());
  comm.allreduce(sums, "the validation all-reduce");
  sum = sums[0], copy_sum = sums[1], scale_sum = sums[2], zero_sum = sums[3], zoom_sum = sums[4];
  ones = sums[5], copy_mismatches = sums[6], count = std::int64_t(sums[7]);
  std::copy(sums.begin() + 8, sums.end(), mismatches.begin());
  ValidationResult r;
  r.mse = sum / double(count);
  r.rmse_kpa = std::sqrt(r.mse) * scale_kpa;
  r.copy_rmse_kpa = std::sqrt(copy_sum / double(count)) * scale_kpa;
  r.scale_rmse_kpa = std::sqrt(scale_sum / double(count)) * scale_kpa;
  r.zero_rmse_kpa = std::sqrt(zero_sum / double(count)) * scale_kpa;
  r.zoom_rmse_kpa = aligned ? std::sqrt(zoom_sum / double(count)) * scale_kpa : NAN;
  if (baselines) {
    for (double m : mismatches) r.binary_r2.push_back(binary_r2_from_counts(m, ones, double(count)));
    r.copy_binary_r2 = binary_r2_from_counts(copy_mismatches, ones, double(count));
  }
  return r;
}

}  // namespace ptnet
