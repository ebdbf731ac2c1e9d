// train/checkpoint.hpp (private to the train stage): the state of a run
// between epochs and checkpoint.pt, which holds it with the weights, the
// optimiser and the RNG so that --resume continues exactly.
//
//   TrainState s;                                   // epoch 0: nothing done
//   save_checkpoint(dir + "/checkpoint.pt", net, optimizer, s);   // atomic
//   s = load_checkpoint(dir + "/checkpoint.pt", net, optimizer);  // CRCs checked first
//
// checkpoint.pt (a LibTorch archive): "model" and "optimizer" archives,
// scalar tensors "epoch", "best_val", "first_val", "best_epoch",
// "bad_epochs", the CPU generator's "rng" state and the "history" text.
#pragma once

#include <cmath>
#include <string>

#include "ptnet/model.hpp"

namespace ptnet {

struct TrainState {
  int epoch = 0;  // epochs completed
  double best_val = INFINITY, first_val = 0;  // validation losses: the best so far, epoch 1's
  int best_epoch = 0, bad_epochs = 0;         // bad: epochs since the best (patience)
  std::string history = "epoch,train_loss,val_loss,lr,seconds\n";
};

// Writes the weights, the optimiser, the state and the RNG to `path` (atomic: a temporary renamed).
void save_checkpoint(const std::string& path, const PressureTransferNet& net, torch::optim::Adam& opt,
                     const TrainState& s);
// Reads them back into net, opt and the default CPU generator; throws Error
// naming the file when it is missing, damaged (zip CRCs) or incomplete.
TrainState load_checkpoint(const std::string& path, PressureTransferNet& net, torch::optim::Adam& opt);

}  // namespace ptnet
