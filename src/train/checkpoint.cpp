// checkpoint.pt: the run's state, weights, optimiser and RNG (checkpoint.hpp).
#include "checkpoint.hpp"

#include <filesystem>

#include "core/zip_check.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
namespace fs = std::filesystem;

void save_checkpoint(const std::string& path, const PressureTransferNet& net, torch::optim::Adam& opt,
                     const TrainState& s) {
  torch::serialize::OutputArchive archive, model, optim;
  write_weights(net, model);
  opt.save(optim);
  archive.write("model", model);
  archive.write("optimizer", optim);
  archive.write("epoch", torch::tensor(std::int64_t(s.epoch)));
  archive.write("best_val", torch::tensor(s.best_val, torch::kFloat64));
  archive.write("first_val", torch::tensor(s.first_val, torch::kFloat64));
  archive.write("best_epoch", torch::tensor(std::int64_t(s.best_epoch)));
  archive.write("bad_epochs", torch::tensor(std::int64_t(s.bad_epochs)));
  archive.write("rng", at::detail::getDefaultCPUGenerator().get_state());
  archive.write("history", c10::IValue(s.history));
  AtomicFile out(path, /*force=*/true);
  archive.save_to(out.temp_path());
  out.commit();
}

TrainState load_checkpoint(const std::string& path, PressureTransferNet& net, torch::optim::Adam& opt) {
  if (!fs::exists(path)) throw Error::in(path, "no checkpoint to resume from");
  verify_zip_file(path);
  torch::serialize::InputArchive archive, model, optim;
  TrainState s;
  try {
    archive.load_from(path, torch::kCPU);
    archive.read("model", model);
    archive.read("optimizer", optim);
  } catch (const c10::Error&) {
    throw Error::in(path, "corrupt or truncated checkpoint");
  }
  read_weights(net, model, path);
  opt.load(optim);
  auto read_t = [&](const char* key) {
    torch::Tensor t;  // fresh: reading into a defined tensor would set_() it
    if (!archive.try_read(key, t)) throw Error::in(path, std::string("checkpoint lacks \"") + key + "\"");
    return t;
  };
  s.epoch = int(read_t("epoch").item<std::int64_t>());
  s.best_val = read_t("best_val").item<double>();
  s.first_val = read_t("first_val").item<double>();
  s.best_epoch = int(read_t("best_epoch").item<std::int64_t>());
  s.bad_epochs = int(read_t("bad_epochs").item<std::int64_t>());
  at::Generator gen = at::detail::getDefaultCPUGenerator();  // a handle on the default generator
  gen.set_state(read_t("rng"));
  c10::IValue h;
  archive.read("history", h);
  s.history = h.toStringRef();
  return s;
}

}  // namespace ptnet
