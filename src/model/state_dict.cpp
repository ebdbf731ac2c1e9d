// Model weights as a PyTorch state dict and back (state_dict.hpp). A Torch
// translation unit of the model stage.
#include "ptnet/state_dict.hpp"

#include <caffe2/serialize/inline_container.h>
#include <torch/csrc/jit/serialization/export.h>
#include <torch/csrc/jit/serialization/pickle.h>
#include <torch/csrc/jit/serialization/pickler.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "core/zip_check.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/model.hpp"
#include "ptnet/strings.hpp"

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

// What torch.save writes for `dict` (a zip archive: data.pkl and one record
// per tensor), in the form PyTorch's torch.load(weights_only=True) accepts:
// torch::pickle_save wraps typed containers in the global
// torch.jit._pickle.restore_type_tag, which the weights-only unpickler
// refuses; this is the same pickle without that tag (the Pickler's
// tag_aggregates off). torch::pickle_load reads both.
std::vector<char> save_plain_dict(const c10::Dict<std::string, torch::Tensor>& dict) {
  std::vector<char> pickle;
  torch::jit::Pickler pickler([&](const char* p, std::size_t n) { pickle.insert(pickle.end(), p, p + n); },
                              /*tensor_table=*/nullptr, /*type_renamer=*/nullptr, /*memoized_class_types=*/nullptr,
                              /*get_tensor_id=*/nullptr, /*tag_aggregates=*/false);
  pickler.protocol();
  pickler.pushIValue(dict);
  pickler.stop();
  std::vector<char> zip;
  caffe2::serialize::PyTorchStreamWriter writer([&](const void* p, std::size_t n) {
    zip.insert(zip.end(), static_cast<const char*>(p), static_cast<const char*>(p) + n);
    return n;
  });
  torch::jit::writeArchiveAndTensors("data", pickle.data(), pickle.size(), pickler.tensorData(), writer);
  writer.writeEndOfFile();
  return zip;
}

// The tensors of a torch.save'd dict, by name; throws Error naming `path`.
c10::Dict<c10::IValue, c10::IValue> read_dict(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw Error::in(path, "no such file (a state dict saved by torch.save)", ErrorKind::not_found);
  verify_zip_file(path);
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw Error::in(path, "cannot read", ErrorKind::io);
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

// Values no training produces (python/ptnet_torch.py check_state_dict holds
// the same rules): NaN or Inf anywhere, a negative BatchNorm running
// variance or batch count, a contact floor outside [0, 1] (the mat's minimum
// reading over the pressure scale).
void check_weight_values(const PressureTransferNet& net, const std::string& path) {
  for (const auto& [name, t] : named_tensors(net)) {
    const auto tensor = [&](const std::string& problem) {
      return Error::in(path, "tensor \"" + name + "\" " + problem);
    };
    if (t.is_floating_point() && !torch::isfinite(t).all().item<bool>())
      throw tensor("has non-finite values (NaN or Inf)");
    const bool count = ends_with(name, "num_batches_tracked"), variance = ends_with(name, "running_var");
    if ((count || variance) && (t < 0).any().item<bool>())
      throw tensor(variance ? "has a negative BatchNorm variance" : "is negative");
    if (name == "contact_floor" && !(t.item<double>() >= 0 && t.item<double>() <= 1))
      throw tensor("is " + number_text(t.item<double>()) + ", expected a value in [0, 1] (normalised pressure)");
  }
}

}  // namespace

void export_state_dict(const std::string& model_dir, const std::string& out_path, bool force) {
  const ModelFiles files(model_dir);
  const std::string config_path = files.config(), weights_path = files.weights();
  note_input(config_path);
  note_input(weights_path);
  check_output_name(out_path, {".pt", ".pth"}, "a PyTorch state dict");
  check_output_path(out_path, force);
  const ModelDir dir = read_model_dir(model_dir);
  PressureTransferNet net(dir.model);
  load_weights(net, weights_path);
  check_weights_digest(*net, recorded_digest(dir, ModelFiles::kWeights), weights_path, config_path);
  c10::Dict<std::string, torch::Tensor> dict;
  for (const auto& [name, tensor] : named_tensors(net)) dict.insert(name, tensor.detach().cpu().contiguous());
  const std::vector<char> bytes = save_plain_dict(dict);
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
                                          arch_name(dir.model.arch) + " in " + ModelFiles(config_dir).config() + "?)");
      if (!it->value().isTensor()) throw Error::in(weights_path, "\"" + name + "\" is not a tensor");
      const torch::Tensor src = it->value().toTensor();
      if (src.sizes() != dst.sizes())
        throw Error::in(weights_path, "tensor \"" + name + "\" has shape " + shape_text(src.sizes()) +
                                          ", the model expects " + shape_text(dst.sizes()) + " (weights and " +
                                          ModelFiles(config_dir).config() + " disagree)");
      dst.copy_(src.to(dst.dtype()));
    }
    for (const auto& entry : dict) {
      const std::string key = entry.key().isString() ? entry.key().toStringRef() : "(a key that is not a string)";
      if (!known.count(key)) throw Error::in(weights_path, "unexpected tensor \"" + key + "\" (not in the " +
                                                               std::string(arch_name(dir.model.arch)) + " model)");
    }
    check_weight_values(net, weights_path);
  }
  make_folder(out_dir);
  std::error_code ec;
  const ModelFiles out(out_dir);
  for (const char* stale : {ModelFiles::kCheckpoint, ModelFiles::kHistory}) fs::remove(out.path(stale), ec);
  dir.path = out_dir;
  dir.integrity = nlohmann::json::object();
  record_digest(dir, ModelFiles::kWeights, weights_digest(*net));
  dir.metrics = nlohmann::json{{"imported_from", weights_path}};
  CommitGroup group;
  save_weights(net, out.weights());
  write_text_file(out.config(), to_json(dir).dump(2) + "\n", /*force=*/true);
  group.commit();
}

}  // namespace ptnet
