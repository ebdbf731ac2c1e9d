// train/model_folder.hpp (private to the train stage): the model folder a
// run writes (config.json, model.pt, checkpoint.pt, history.csv) made ready
// before the run, and removed again when a fresh run fails while setting up.
// No Torch.
//
//   prepare_out_dir("model/", o);           // created, or emptied with o.force
//   LeftoverGuard leftovers("model/", o.resume);
//   ...                                     // an exception here removes what was written
//   leftovers.done();                       // from here a failure keeps the checkpoint
#pragma once

#include <string>
#include <utility>

#include "ptnet/train.hpp"

namespace ptnet {

// o.resume: the folder must exist. Otherwise it is created (its parent must
// exist), or an empty one is taken, or with o.force the model files of an
// existing one are removed; throws Error naming the folder.
void prepare_out_dir(const std::string& dir, const TrainOptions& o);
// The same checks, changing nothing: train() makes them before any work
// (before the ranks meet and the windows are indexed).
void check_out_dir(const std::string& dir, const TrainOptions& o);

// Removes what a fresh run wrote when it fails while setting up (before the
// first epoch starts: bad --init weights, memory, data): config.json,
// checkpoint.pt, history.csv and the folder if it is then empty. Failures in
// the epochs keep the last checkpoint and say so; a resumed run is left as is.
class LeftoverGuard {
 public:
  LeftoverGuard(std::string dir, bool resume) : dir_(std::move(dir)), active_(!resume) {}
  ~LeftoverGuard();
  void done() { active_ = false; }

 private:
  std::string dir_;
  bool active_;
};

}  // namespace ptnet
