// train/loss_validation.hpp (private to the train stage): what training
// minimises and how validation measures it. The loss of a micro-batch, and
// a pass over the validation windows: normalised MSE and, with baselines,
// RMSE in kPa beside the naive baselines and the binary R^2 of the output
// at each candidate contact threshold.
//
//   torch::Tensor l = training_loss(o, net->forward_parts(b.x, b.sa, b.ta), b.y);
//   ValidationResult v = validate_model(net, batcher, index, o, scale_kpa, /*baselines=*/true, comm);
//   v.binary_r2[c];     // at kThresholdCandidatesKpa[c]
//
// Dimension legend: N windows, T window frames, H x W mat cells.
#pragma once

#include <cmath>
#include <iterator>
#include <vector>

#include "batcher.hpp"
#include "distributed/communicator.hpp"
#include "ptnet/model.hpp"
#include "ptnet/train.hpp"
#include "window_index.hpp"

namespace ptnet {

// Content loss (MSE) on the output ReLU(raw), except that cells whose truth
// is > 0 use the raw value: their gradient never dies (see forward_raw).
// Equal to the MSE of the output wherever raw >= 0 or truth == 0. With a
// contact head, plus contact_weight x the cross-entropy of its logits against
// the truth's contact (> 0).
// truth, raw.pressure: [N,T,H,W] normalised; raw.contact: logits [N,T,H,W] or undefined.
torch::Tensor training_loss(const TrainOptions& o, const PressureTransferNetImpl::Raw& raw,
                            const torch::Tensor& truth);

// Candidate output activation thresholds (kPa) for the contact fit.
inline constexpr double kThresholdCandidatesKpa[] = {0.5, 1, 1.5, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40};
inline constexpr int kCandidates = int(std::size(kThresholdCandidatesKpa));

struct ValidationResult {
  double mse = 0;                       // normalised
  double rmse_kpa = 0, copy_rmse_kpa = 0, scale_rmse_kpa = 0, zero_rmse_kpa = 0;
  double zoom_rmse_kpa = NAN;           // the aligned (zoomed) source, when the model aligns
  // With baselines: binary R^2 (cells > kContactKpa) of the output zeroed
  // below each candidate threshold, and of the copy baseline.
  std::vector<double> binary_r2;        // [kCandidates]
  double copy_binary_r2 = 0;
};

// Distributed: the micro-batches are dealt round-robin to the ranks and the
// sums all-reduced, so every rank gets the whole validation set's result.
// `mirrored`: the network's output averaged as at inference with ModelConfig::mirror.
ValidationResult validate_model(PressureTransferNet& net, Batcher& batcher, const WindowIndex& index,
                                const TrainOptions& o, double scale_kpa, bool baselines, Communicator& comm,
                                bool mirrored = false);

}  // namespace ptnet
