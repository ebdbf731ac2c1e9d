// ptnet export / ptnet import-weights: a model folder's weights as a PyTorch
// state dict (torch.load; python/ptnet_torch.py), and a state dict saved in
// PyTorch back into a model folder.
//
//   ptnet export --model model/ --out weights.pt
//   ptnet import-weights --weights tuned.pt --config model/ --out tuned_model/
#include "command.hpp"
#include "ptnet/state_dict.hpp"

namespace ptnet::cli::cmd_export {
namespace {

struct ExportCli {
  std::string model, out;
  bool force = false;
};

struct ImportWeightsCli {
  std::string weights, config, out;
  bool force = false;
};

void setup(CLI::App& app) {
  auto e = std::make_shared<ExportCli>();
  auto* cmd = app.add_subcommand(
      "export",
      "Write a model folder's weights as a PyTorch state dict (torch.load reads it; the modules of\n"
      "python/ptnet_torch.py have the same parameter names). The architecture and normalisation stay in\n"
      "config.json (docs/python.md).");
  cmd->add_option("--model", e->model, "Model folder (ptnet train)")->required();
  cmd->add_option("--out", e->out, "Output file, e.g. weights.pt")->required();
  cmd->add_flag("--force", e->force, "Overwrite the output");
  cmd->callback([e]() { export_state_dict(e->model, e->out, e->force); });

  auto i = std::make_shared<ImportWeightsCli>();
  auto* imp = app.add_subcommand(
      "import-weights",
      "Make a model folder from a state dict saved in PyTorch (python/ptnet_torch.py save_state_dict,\n"
      "or torch.save of a dict of tensors) and the config.json of the model folder it was exported from\n"
      "(same architecture and normalisation): OUT/config.json + OUT/model.pt, usable by transfer,\n"
      "evaluate and train --init.");
  imp->add_option("--weights", i->weights, "State dict file (torch.save of a plain dict of tensors)")->required();
  imp->add_option("--config", i->config, "Model folder whose config.json describes the weights")->required();
  imp->add_option("--out", i->out, "Model folder to create")->required();
  imp->add_flag("--force", i->force, "Overwrite an existing model folder");
  imp->callback([i]() { import_state_dict(i->weights, i->config, i->out, i->force); });
}

}  // namespace

PTNET_COMMAND(58, setup);

}  // namespace ptnet::cli::cmd_export
