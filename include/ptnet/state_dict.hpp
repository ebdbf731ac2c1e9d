// ptnet/state_dict.hpp: a model folder's weights as a PyTorch state dict, and
// back (no Torch in this header; the CLI's `ptnet export` / `import-weights`).
//
//   ptnet::export_state_dict("model/", "weights.pt", /*force=*/false);
//   // Python: net, cfg = ptnet_torch.load("model/", "weights.pt")  (python/ptnet_torch.py)
//   ptnet::import_state_dict("tuned.pt", "model/", "tuned_model/", /*force=*/false);
//
// The file is what Python's torch.save writes for a dict of tensors (a zip
// archive holding data.pkl; LibTorch's torch::pickle_save): keys are the
// module's parameter and buffer names ("conv1.weight", "bn1.running_mean",
// "frame.film2.bias", "contact_floor", ...), the same as state_dict() of the
// modules in python/ptnet_torch.py; float32 tensors on the CPU
// (num_batches_tracked int64). The architecture and the normalisation are not
// in it: they stay in config.json (docs/python.md). Its pickle names no global
// but tensor rebuilding ones, so PyTorch's torch.load(weights_only=True)
// reads it.
#pragma once

#include <string>

namespace ptnet {

// Reads MODEL_DIR (config.json, model.pt: validated and digest-checked as by
// Transfer) and writes its weights to `out_path` as a state dict. Throws
// Error naming the file.
void export_state_dict(const std::string& model_dir, const std::string& out_path, bool force);

// Reads a state dict saved by torch.save (a plain dict of tensors: LibTorch
// cannot read the OrderedDict of state_dict() itself) for the architecture in CONFIG_DIR/config.json, and writes a model folder
// `out_dir`: config.json (config_dir's, with the new weights' digest; its
// training metrics replaced by {"imported_from": weights_path}) and model.pt.
// Every key of the model must be present with its shape, and no other key
// (Error "weights.pt: missing tensor \"conv1.weight\"", "... unexpected
// tensor \"fc.weight\"", "... has shape [4, 1, 3, 3], the model expects ..."),
// and every value finite, BatchNorm running variances and batch counts >= 0,
// contact_floor in [0, 1] ("weights.pt: tensor \"bn1.running_var\" has a
// negative BatchNorm variance").
void import_state_dict(const std::string& weights_path, const std::string& config_dir, const std::string& out_dir,
                       bool force);

}  // namespace ptnet
