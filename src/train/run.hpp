// train/run.hpp (private to the train stage): what the phases of train()
// share. train.cpp holds the run's setup, its final metrics and train()
// itself; epochs.cpp the epochs (one optimiser step per batch, validation,
// the best weights, the checkpoint and the history after each).
//
// Dimension legend: N windows in a batch, T window frames, H x W mat cells,
// A = 3 attributes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "batcher.hpp"
#include "checkpoint.hpp"
#include "distributed/communicator.hpp"
#include "ptnet/io.hpp"
#include "ptnet/model.hpp"
#include "ptnet/train.hpp"
#include "window_index.hpp"

namespace ptnet {

// What the phases share: the model folder's files and what goes into config.json.
struct TrainRun {
  const PressureSource& source;
  TrainOptions o;  // a copy: plan_model settles contact_weight
  std::filesystem::path dir;
  std::string config_path, ckpt_path, best_path;
  torch::Device device;
  ModelDir md;        // written to config.json
  ModelDir previous;  // --resume: the folder's config; --init: the other model's
  std::string digest;
  Communicator& comm;  // the ranks (a world of one when not distributed)
  // Distributed: the best weights so far, kept by the ranks that do not
  // write the folder (they may not see rank 0's model.pt).
  std::vector<torch::Tensor> best_snapshot;

  TrainRun(const PressureSource& src, const std::string& out_dir, const TrainOptions& options, Communicator& c)
      : source(src), o(options), dir(out_dir), config_path(ModelFiles(out_dir).config()),
        ckpt_path(ModelFiles(out_dir).checkpoint()), best_path(ModelFiles(out_dir).weights()),
        device(parse_device(options.device)), comm(c) {}
  bool writes() const { return comm.rank() == 0; }  // rank 0 alone writes the model folder
  void log(const std::string& line) const {
    if (o.progress) o.progress(progress_line("train", line));
  }
  void write_config() {
    if (writes()) write_text_file(config_path, to_json(md).dump(2) + "\n", /*force=*/true);
  }
};

// `v` printed with the printf format `f` ("%.3g").
std::string format_number(const char* f, double v);

// Parameters and buffers, in a fixed order (the best-weights snapshot).
std::vector<torch::Tensor> weight_tensors(const PressureTransferNet& net);

// The epochs, from s.epoch until the last one or early stopping (epochs.cpp).
void run_epochs(TrainRun& run, PressureTransferNet& net, torch::optim::Adam& optimizer, Batcher& batcher,
                const WindowIndex& index, TrainState& s);

}  // namespace ptnet
