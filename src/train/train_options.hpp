// train/train_options.hpp (private to the train stage): what train() does
// with TrainOptions before the run: the checks, the learning-rate schedule
// and the options as config.json records them. (The presets, summary() and
// set_arch() are TrainOptions' members: ptnet/train.hpp.) No Torch.
//
//   check_options(o);                       // throws Error naming the option
//   const double lr = lr_at(o, epoch0);     // the step schedule, epoch0 0-based
//   md.options = options_json(o);           // config.json's "options"
#pragma once

#include <nlohmann/json.hpp>

#include "ptnet/train.hpp"

namespace ptnet {

// Throws Error for values train() cannot run with ("epochs: must be >= 1, found 0").
void check_options(const TrainOptions& o);
// The learning rate of epoch `epoch0` (0-based): lr halved every lr_halve_every epochs.
double lr_at(const TrainOptions& o, int epoch0);
// The options as config.json records them (and the ranks compare).
nlohmann::json options_json(const TrainOptions& o);

}  // namespace ptnet
