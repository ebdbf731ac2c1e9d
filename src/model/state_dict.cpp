// Model weights as a PyTorch state dict and back (state_dict.hpp). A Torch
// translation unit of the model stage.
#include "ptnet/state_dict.hpp"

#include <torch/csrc/jit/serialization/pickle.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/model.hpp"
#include "ptnet/zip_check.hpp"

namespace ptnet {
namespace fs = std::filesystem;

namespace {

// Every parameter, then every buffer: the names state_dict() has in PyTorch.
std::vector<std::pair<std::string, torch::Tensor>> named_tensors(const PressureTransferNet& net) {
  std::vector<std::pair<std::string, torch::Tensor>> out;
  for (const auto& item : net->named_parameters(/*recurse=*/true)) out.emplace_back(item.key(), item.value());
  for (const auto& item : net->named_buffers(/*recurse=*/true)) out.emplace_back(item.key(), item.value());
  return out;
}

std::string shape_text(c10::IntArrayRef sizes) {
  std::ostringstream s;
  s << sizes;
  return s.str();
}

// The tensors of a torch.save'd dict, by name; throws Error naming `path`.
c10::Dict<c10::IValue, c10::IValue> read_dict(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error::in(path, "no such file (a state dict saved by torch.save)");
  verify_zip_file(path);
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw Error::in(path, "cannot read");
  // LibTorch 1.13's unpickler reads a plain dict, not the OrderedDict (with
  // its _metadata) that state_dict() returns.
  const std::string how = "save a plain dict: ptnet_torch.save_state_dict(net, FILE) or "
                          "torch.save(dict(net.state_dict()), FILE)";
  c10::IValue value;
  try {
    value = torch::pickle_load(bytes);
  } catch (const c10::Error&) {
    throw Error::in(path, "not a plain dict of tensors saved by torch.save (" + how + ")");
  }
  if (!value.isGenericDict()) throw Error::in(path, "expected a dict of tensors, found " + value.tagKind() + " (" + how + ")");
  return value.toGenericDict();
}

}  // namespace

void export_state_dict(const std::string& model_dir, const std::string& out_path, bool force) {
  const std::string config_path = (fs::path(model_dir) / "config.json").string();
  const std::string weights_path = (fs::path(model_dir) / "model.pt").string();
  note_input(config_path);
  note_input(weights_path);
  check_output_path(out_path, force);
  const ModelDir dir = read_model_dir(model_dir);
  PressureTransferNet net(dir.model);
  load_weights(net, weights_path);
  check_weights_digest(*net, recorded_digest(dir, "model.pt"), weights_path, config_path);
  c10::Dict<std::string, torch::Tensor> dict;
  for (const auto& [name, tensor] : named_tensors(net)) dict.insert(name, tensor.detach().cpu().contiguous());
  const std::vector<char> bytes = torch::pickle_save(dict);
  write_text_file(out_path, std::string(bytes.begin(), bytes.end()), force);
}

void import_state_dict(const std::string& weights_path, const std::string& config_dir, const std::string& out_dir,
                       bool force) {
  ModelDir dir = read_model_dir(config_dir);
  const auto dict = read_dict(weights_path);
  check_output_folder(out_dir, force);
  PressureTransferNet net(dir.model);
  {
    torch::NoGradGuard no_grad;
    std::set<std::string> known;
    for (auto& [name, dst] : named_tensors(net)) {
      known.insert(name);
      auto it = dict.find(c10::IValue(name));
      if (it == dict.end())
        throw Error::in(weights_path, "missing tensor \"" + name + "\" (saved from another architecture than " +
                                          arch_name(dir.model.arch) + " in " + config_dir + "/config.json?)");
      if (!it->value().isTensor()) throw Error::in(weights_path, "\"" + name + "\" is not a tensor");
      const torch::Tensor src = it->value().toTensor();
      if (src.sizes() != dst.sizes())
        throw Error::in(weights_path, "tensor \"" + name + "\" has shape " + shape_text(src.sizes()) +
                                          ", the model expects " + shape_text(dst.sizes()) + " (weights and " +
                                          config_dir + "/config.json disagree)");
      dst.copy_(src.to(dst.dtype()));
    }
    for (const auto& entry : dict) {
      const std::string key = entry.key().isString() ? entry.key().toStringRef() : "(a key that is not a string)";
      if (!known.count(key)) throw Error::in(weights_path, "unexpected tensor \"" + key + "\" (not in the " +
                                                               std::string(arch_name(dir.model.arch)) + " model)");
    }
    for (const auto& p : net->parameters())
      if (!torch::isfinite(p).all().item<bool>()) throw Error::in(weights_path, "non-finite weights (NaN or Inf)");
  }
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error::in(out_dir, "cannot create folder: " + ec.message());
  for (const char* stale : {"checkpoint.pt", "history.csv"}) fs::remove(fs::path(out_dir) / stale, ec);
  dir.path = out_dir;
  dir.integrity = nlohmann::json::object();
  record_digest(dir, "model.pt", weights_digest(*net));
  dir.metrics = nlohmann::json{{"imported_from", weights_path}};
  CommitGroup group;
  save_weights(net, (fs::path(out_dir) / "model.pt").string());
  write_text_file((fs::path(out_dir) / "config.json").string(), to_json(dir).dump(2) + "\n", /*force=*/true);
  group.commit();
}

}  // namespace ptnet
