// The epochs of train() (run.hpp): each epoch's optimiser steps over its
// windows (a step per batch, gradients accumulated over micro-batches and,
// distributed, summed over the ranks), its validation, and what is recorded
// after it (the best weights, the history, the checkpoint, config.json);
// distributed, the BatchNorm statistics the ranks share (SharedBatchNorm).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "loss_validation.hpp"
#include "ptnet/error.hpp"
#include "run.hpp"
#include "train_options.hpp"

namespace ptnet {
namespace {

// Training windows of one epoch: all (shuffled) or `samples_per_epoch` drawn
// uniformly, from a generator seeded by (seed, epoch) so resume matches.
std::vector<std::int64_t> epoch_order(const TrainOptions& o, const WindowIndex& index, int epoch0) {
  std::mt19937_64 rng(o.seed * 0x9E3779B97F4A7C15ull + std::uint64_t(epoch0) + 1);
  const std::int64_t total = index.train_size();
  std::vector<std::int64_t> order;
  if (o.samples_per_epoch > 0 && o.samples_per_epoch < total) {
    std::uniform_int_distribution<std::int64_t> pick(0, total - 1);
    for (std::int64_t i = 0; i < o.samples_per_epoch; ++i) order.push_back(pick(rng));
  } else {
    order.resize(std::size_t(total));
    for (std::int64_t i = 0; i < total; ++i) order[std::size_t(i)] = i;
    for (std::int64_t i = total - 1; i > 0; --i) {
      std::uniform_int_distribution<std::int64_t> pick(0, i);
      std::swap(order[std::size_t(i)], order[std::size_t(pick(rng))]);
    }
  }
  return order;
}

// BatchNorm running statistics of a step whose micro-batches are spread over
// the ranks. One process updates them micro-batch after micro-batch:
// r <- (1 - a) r + a x_m, so after M of them r = (1 - a)^M r0 + sum_m
// (1 - a)^(M-1-m) a x_m. Each rank runs its micro-batches from zeroed
// buffers (the update is then a x_m), adds them up with that decay, and the
// sum over the ranks (all-reduced with the gradients) completes the formula.
// Training arithmetic, not networking: the caller all-reduces sums().
//
//   SharedBatchNorm bn(*net);
//   bn.begin_step();
//   for m in this rank's micro-batches: bn.before_micro_batch(); forward; bn.after_micro_batch(m, M);
//   comm.allreduce(gradients + bn.sums()); bn.end_step(M);
class SharedBatchNorm {
 public:
  // The BatchNorm2d layers of `net` that track running statistics.
  explicit SharedBatchNorm(torch::nn::Module& net);
  void begin_step();
  void before_micro_batch();
  void after_micro_batch(int m, int count);
  std::vector<torch::Tensor>& sums() { return sums_; }  // all-reduced by the caller
  void end_step(int count);

 private:
  struct Layer {
    torch::Tensor mean, var, batches;  // the layer's running_mean, running_var, num_batches_tracked
    double momentum = 0.1;
  };
  std::vector<Layer> layers_;
  std::vector<std::array<torch::Tensor, 3>> start_;  // per layer: mean, var, batches at the step's start
  std::vector<torch::Tensor> sums_;                  // per layer: decayed mean, var sums of this rank
};

SharedBatchNorm::SharedBatchNorm(torch::nn::Module& net) {
  for (const auto& m : net.modules(/*include_self=*/false))
    if (auto* bn = dynamic_cast<torch::nn::BatchNorm2dImpl*>(m.get()); bn && bn->options.track_running_stats())
      layers_.push_back({bn->running_mean, bn->running_var, bn->num_batches_tracked,
                         bn->options.momentum().value_or(0.1)});
}

void SharedBatchNorm::begin_step() {
  start_.clear();
  sums_.clear();
  for (const Layer& l : layers_) {
    start_.push_back({l.mean.clone(), l.var.clone(), l.batches.clone()});
    sums_.push_back(torch::zeros_like(l.mean));
    sums_.push_back(torch::zeros_like(l.var));
  }
}

void SharedBatchNorm::before_micro_batch() {
  torch::NoGradGuard no_grad;
  for (Layer& l : layers_) l.mean.zero_(), l.var.zero_();
}

void SharedBatchNorm::after_micro_batch(int m, int count) {
  torch::NoGradGuard no_grad;
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    const double decay = std::pow(1 - layers_[i].momentum, count - 1 - m);
    sums_[2 * i].add_(layers_[i].mean, decay);
    sums_[2 * i + 1].add_(layers_[i].var, decay);
  }
}

void SharedBatchNorm::end_step(int count) {
  torch::NoGradGuard no_grad;
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    const double decay = std::pow(1 - layers_[i].momentum, count);
    layers_[i].mean.copy_(start_[i][0] * decay + sums_[2 * i]);
    layers_[i].var.copy_(start_[i][1] * decay + sums_[2 * i + 1]);
    layers_[i].batches.copy_(start_[i][2] + count);
  }
}

// One epoch of optimiser steps (epoch0 0-based); the mean training loss.
// Distributed: each rank runs the micro-batches m with m % ranks == rank;
// the gradients (each micro-batch's loss already weighted by its share of
// the whole batch), the BatchNorm statistics and the loss are summed over
// the ranks before the step.
double train_epoch(const TrainRun& run, PressureTransferNet& net, torch::optim::Adam& optimizer, Batcher& batcher,
                   const WindowIndex& index, int epoch0, const TrainState& s) {
  const TrainOptions& o = run.o;
  Communicator& comm = run.comm;
  SharedBatchNorm shared_bn(*net);
  const std::vector<torch::Tensor> params = net->parameters();
  net->train();
  const auto order = epoch_order(o, index, epoch0);
  double loss_sum = 0;
  std::int64_t seen = 0;
  std::vector<WindowRef> refs;
  for (std::size_t i = 0; i < order.size(); i += std::size_t(o.batch)) {
    refs.clear();
    for (std::size_t j = i; j < std::min(order.size(), i + std::size_t(o.batch)); ++j)
      refs.push_back(index.train(order[j]));
    // One optimiser step per batch; gradients accumulate over micro-batches,
    // each loss weighted by its share of the batch (= the batch mean).
    optimizer.zero_grad();
    double l = 0;
    const std::size_t micro = std::size_t(std::max(1, o.micro_batch));
    const int micro_batches = int((refs.size() + micro - 1) / micro);
    if (comm.distributed()) shared_bn.begin_step();
    for (std::size_t m = 0; m < refs.size(); m += micro) {
      const int k = int(m / micro);
      if (k % comm.size() != comm.rank()) continue;
      const std::vector<WindowRef> part(refs.begin() + std::ptrdiff_t(m),
                                        refs.begin() + std::ptrdiff_t(std::min(refs.size(), m + micro)));
      if (comm.distributed()) shared_bn.before_micro_batch();
      Batch b = batcher.load(part);
      if (o.crop_rows > 0 && run.md.model.arch == Arch::frame) crop_to_pressure(b, o.crop_rows);
      if (o.mirror) mirror_every_second(b);
      auto loss = training_loss(o, net->forward_parts(b.x, b.sa, b.ta), b.y) *
                  (double(part.size()) / double(refs.size()));
      const double part_loss = loss.item<double>();
      if (!std::isfinite(part_loss))
        throw Error("training diverged: loss is " +
                    std::string(std::isnan(part_loss) ? "NaN" : "infinite") + " at epoch " +
                    std::to_string(epoch0 + 1) + ", batch " + std::to_string(i / o.batch + 1) +
                    " (try a lower " + field_text("lr") + "); the last good checkpoint (epoch " +
                    std::to_string(s.epoch) + ") is kept in " + run.ckpt_path);
      loss.backward();
      l += part_loss;
      if (comm.distributed()) shared_bn.after_micro_batch(k, micro_batches);
    }
    if (comm.distributed()) {
      std::vector<torch::Tensor> summed;
      for (const auto& p : params) {
        if (!p.grad().defined()) p.mutable_grad() = torch::zeros_like(p);
        summed.push_back(p.grad());
      }
      for (const auto& t : shared_bn.sums()) summed.push_back(t);
      summed.push_back(torch::tensor(float(l)));
      comm.allreduce(summed, "the gradient all-reduce (epoch " + std::to_string(epoch0 + 1) + ")");
      shared_bn.end_step(micro_batches);
      l = double(summed.back().item<float>());
    }
    optimizer.step();
    loss_sum += l * double(refs.size());
    seen += std::int64_t(refs.size());
    if (o.progress) {
      Progress p = progress_count("train", seen, std::int64_t(order.size()), "windows");
      p.step = epoch0 + 1;
      p.steps = o.epochs;
      o.progress(p);
    }
  }
  return loss_sum / double(seen);
}

// After an epoch: the best weights when validation improved, the history,
// the checkpoint and config.json; the epoch's log line.
void record_epoch(TrainRun& run, PressureTransferNet& net, torch::optim::Adam& optimizer, TrainState& s, int epoch0,
                  double train_loss, double val_loss, double lr, double secs) {
  s.epoch = epoch0 + 1;
  if (epoch0 == 0) s.first_val = val_loss;
  if (val_loss < s.best_val) {
    s.best_val = val_loss;
    s.best_epoch = epoch0 + 1;
    s.bad_epochs = 0;
    if (run.writes()) {
      save_weights(net, run.best_path);
      record_digest(run.md, ModelFiles::kWeights, weights_digest(*net));
      run.write_config();
    } else {
      run.best_snapshot.clear();
      for (const auto& t : weight_tensors(net)) run.best_snapshot.push_back(t.detach().clone());
    }
  } else {
    ++s.bad_epochs;
  }
  s.history += std::to_string(epoch0 + 1) + "," + format_number("%.6g", train_loss) + "," +
               format_number("%.6g", val_loss) + "," + format_number("%.6g", lr) + "," + format_number("%.3f", secs) +
               "\n";
  if (run.writes()) {
    save_checkpoint(run.ckpt_path, net, optimizer, s);
    record_digest(run.md, ModelFiles::kCheckpoint, weights_digest(*net), s.epoch);
    run.write_config();
    write_text_file(ModelFiles(run.dir.string()).history(), s.history, /*force=*/true);
  }
  char line[160];
  std::snprintf(line, sizeof line, "[epoch %d/%d] train %.6f val %.6f lr %.1e %.1f s", epoch0 + 1, run.o.epochs,
                train_loss, val_loss, lr, secs);
  run.log(line);
}

}  // namespace

void run_epochs(TrainRun& run, PressureTransferNet& net, torch::optim::Adam& optimizer, Batcher& batcher,
                const WindowIndex& index, TrainState& s) {
  const TrainOptions& o = run.o;
  const bool finished_before = s.epoch >= o.epochs || s.bad_epochs >= o.patience;
  for (int e = s.epoch; e < o.epochs && s.bad_epochs < o.patience && !finished_before; ++e) {
    const auto t0 = std::chrono::steady_clock::now();
    const double lr = lr_at(o, e);
    for (auto& group : optimizer.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
    const double train_loss = train_epoch(run, net, optimizer, batcher, index, e, s);
    const ValidationResult v = validate_model(net, batcher, index, o, run.md.norm.pressure_scale_kpa, false, run.comm);
    if (!std::isfinite(v.mse))
      throw Error("training diverged: validation loss is not finite at epoch " + std::to_string(e + 1) +
                  "; the last good checkpoint (epoch " + std::to_string(s.epoch) + ") is kept in " + run.ckpt_path);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    record_epoch(run, net, optimizer, s, e, train_loss, v.mse, lr, secs);
  }
}

}  // namespace ptnet
