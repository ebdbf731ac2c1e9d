// train/train_options.hpp (private to the train stage): what train() does
// with TrainOptions before the run: the learning-rate schedule and the options
// as config.json records them. (The presets, summary(), set_arch() and
// check_options() are public: ptnet/train.hpp.) No Torch.
//
//   const double lr = lr_at(o, epoch0);     // the step schedule, epoch0 0-based
//   md.options = options_json(o);           // config.json's "options"
#pragma once

#include <nlohmann/json.hpp>

#include "ptnet/train.hpp"

namespace ptnet {

// The learning rate of epoch `epoch0` (0-based): lr halved every lr_halve_every epochs.
double lr_at(const TrainOptions& o, int epoch0);
// The options as config.json records them (and the ranks compare).
nlohmann::json options_json(const TrainOptions& o);

}  // namespace ptnet
