// train(): the run and its phases, in order: plan the model, index the
// windows, build the network, start or resume, then the epochs (epochs.cpp:
// Adam with a step learning-rate schedule, early stopping, a checkpoint per
// epoch) and the final metrics of the best weights. What the phases share:
// run.hpp. The pieces they run: the options (train_options.cpp), the
// batches (batcher.cpp), the loss and validation (loss_validation.cpp),
// checkpoint.pt (checkpoint.cpp), the model folder (model_folder.cpp) and
// the ranks (src/distributed/communicator.cpp).
//
// Dimension legend: N windows in a batch, T window frames, H x W mat cells,
// A = 3 attributes.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/rate.hpp"
#include "loss_validation.hpp"
#include "model_folder.hpp"
#include "ptnet/error.hpp"
#include "run.hpp"
#include "source.hpp"
#include "train_options.hpp"

namespace ptnet {
namespace fs = std::filesystem;
using nlohmann::json;

std::string format_number(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::vector<torch::Tensor> weight_tensors(const PressureTransferNet& net) {
  std::vector<torch::Tensor> out;
  for (const auto& p : net->parameters()) out.push_back(p);
  for (const auto& b : net->buffers()) out.push_back(b);
  return out;
}

namespace {

// ---- the phases of train(), in order (the epochs: epochs.cpp)

// The architecture from the options, the resumed folder or the --init model,
// checked against the data's mat and frame rate and the available memory.
void plan_model(TrainRun& run) {
  const PressureSource& source = run.source;
  TrainOptions& o = run.o;
  const MatSpec mat = source.mat();
  ModelDir& md = run.md;
  md.path = run.dir.string();
  md.mat = mat;
  md.fps = source.fps();
  md.model = o.model;
  md.model.rows = mat.rows;
  md.model.cols = mat.cols;
  run.digest = source_digest(source);
  if (o.resume) {
    run.previous = read_model_dir(md.path);
    const std::string recorded = run.previous.data.value("digest", "");
    if (recorded != run.digest)
      throw Error::in(run.config_path, "was trained on other data (digest " + run.previous.data.value("digest", "?") +
                                           ", " + source.path() + " has " + run.digest + "); cannot resume");
    md.model = run.previous.model;
    md.integrity = run.previous.integrity;
  } else if (!o.init.empty()) {
    run.previous = read_model_dir(o.init);
    md.model = run.previous.model;  // fine-tuning keeps the architecture
  }
  const ModelDir& previous = run.previous;
  // A contact head trains with a weight: the given one, else the one it was trained with.
  if (md.model.contact && o.contact_weight <= 0) o.contact_weight = previous.options.value("contact_weight", 0.0);
  if (md.model.contact && !(o.contact_weight > 0))
    throw Error(field_text("contact_weight") + ": a model with a contact head needs a weight > 0");
  if (!md.model.contact) o.contact_weight = 0;
  if ((o.resume || !o.init.empty()) && !same_rate(source.fps(), previous.fps))
    throw Error::in(source.path(), "is at " + number_text(source.fps()) + " fps, the model at " +
                                       number_text(previous.fps) + " fps");
  if (md.model.rows != mat.rows || md.model.cols != mat.cols)
    throw Error::in(source.path(), "mat is " + std::to_string(mat.rows) + " x " + std::to_string(mat.cols) +
                                       ", the model was built for " + std::to_string(md.model.rows) + " x " +
                                       std::to_string(md.model.cols));
  validate(md.model);
  check_memory(model_memory_bytes(md.model, o.micro_batch, /*training=*/true), md.path,
               "the model (" + std::to_string(parameter_count(md.model)) + " parameters) in training");
}

// The lazy window index and the normalisation (fitted, or the previous
// model's), recorded in config.json's data and options.
WindowIndex index_windows(TrainRun& run) {
  const TrainOptions& o = run.o;
  WindowOptions wo;
  wo.window = run.md.model.window;
  wo.stride = o.stride;
  wo.seed = o.seed;
  wo.identity_pairs = o.identity_pairs;
  WindowIndex index = WindowIndex::build(run.source, wo);
  if (index.val_size() == 0)
    throw Error::in(run.source.path(), "motions too short for a validation split (need >= " +
                                           std::to_string(3 * wo.window) + " frames)");
  run.md.norm = (o.resume || !o.init.empty()) ? run.previous.norm : fit_normalisation(run.source, index);
  run.md.data = json{{"path", run.source.path()},      {"digest", run.digest},
                     {"pairs", index.pairs().size()},  {"motions", index.motions().size()},
                     {"train_windows", index.train_size()}, {"val_windows", index.val_size()},
                     {"protocol", "role=retargeted, take=1; 9:1 per-motion time blocks"}};
  run.md.options = options_json(o);
  return index;
}

// The network, seeded, with the --init model's weights when fine-tuning.
PressureTransferNet build_network(const TrainRun& run) {
  const TrainOptions& o = run.o;
  torch::manual_seed(o.seed);
  PressureTransferNet net(run.md.model);
  if (run.md.model.contact) net->set_contact_floor(run.md.norm.min_reading_kpa / run.md.norm.pressure_scale_kpa);
  if (!o.init.empty() && !o.resume) {
    const ModelFiles init(o.init);
    load_weights(net, init.weights());
    check_weights_digest(*net, recorded_digest(run.previous, ModelFiles::kWeights), init.weights(), init.config());
  }
  net->to(run.device);
  return net;
}

// --resume: the checkpoint's state (its weights checked against config.json);
// a fresh run: the initial weights as the epoch-0 checkpoint.
TrainState start_or_resume(TrainRun& run, PressureTransferNet& net, torch::optim::Adam& optimizer) {
  TrainState s;
  if (run.o.resume) {
    s = load_checkpoint(run.ckpt_path, net, optimizer);
    int recorded_epoch = -1;
    const std::string recorded = recorded_digest(run.previous, ModelFiles::kCheckpoint, &recorded_epoch);
    // A kill between the checkpoint's rename and config.json's leaves the
    // config one epoch behind: that checkpoint passed its CRCs and is taken.
    if (recorded_epoch != s.epoch - 1) check_weights_digest(*net, recorded, run.ckpt_path, run.config_path);
  } else if (run.writes()) {
    save_checkpoint(run.ckpt_path, net, optimizer, s);  // epoch 0: the initial weights
    record_digest(run.md, ModelFiles::kCheckpoint, weights_digest(*net), 0);
    run.write_config();
  }
  return s;
}

void log_setup(const TrainRun& run, const WindowIndex& index, const PressureTransferNet& net, const TrainState& s) {
  const ModelConfig& m = run.md.model;
  run.log("train: " + std::to_string(index.pairs().size()) + " pairs, " + std::to_string(index.train_size()) +
          " training / " + std::to_string(index.val_size()) + " validation windows, " +
          std::to_string(parameter_count(*net)) + " parameters (" + arch_name(m.arch) + " " +
          std::to_string(m.channels[0]) + "/" + std::to_string(m.channels[1]) + "/" +
          std::to_string(m.channels[2]) + "), pressure scale " + format_number("%.3g", run.md.norm.pressure_scale_kpa) +
          " kPa, " + std::to_string(torch::get_num_threads()) + " threads" +
          (run.comm.distributed() ? ", " + std::to_string(run.comm.size()) + " ranks" : "") +
          (run.o.resume ? ", resuming after epoch " + std::to_string(s.epoch) : ""));
  const int micro_batches = (run.o.batch + run.o.micro_batch - 1) / run.o.micro_batch;
  if (run.comm.size() > micro_batches)
    run.log("train: warning: " + std::to_string(micro_batches) + " micro-batch(es) per step for " +
            std::to_string(run.comm.size()) +
            " ranks: some ranks idle (set micro_batch to at most batch / ranks)");
}

// The best weights on the validation windows: RMSE beside the baselines,
// binary R^2, the fitted contact threshold; into config.json and the result.
TrainResult final_metrics(TrainRun& run, PressureTransferNet& net, Batcher& batcher, const WindowIndex& index,
                          const TrainState& s, std::chrono::steady_clock::time_point t_start) {
  const TrainOptions& o = run.o;
  ModelDir& md = run.md;
  if (!run.best_snapshot.empty()) {  // a rank that does not write: its copy of the best weights
    torch::NoGradGuard no_grad;
    const auto tensors = weight_tensors(net);
    for (std::size_t i = 0; i < tensors.size(); ++i) tensors[i].copy_(run.best_snapshot[i]);
  } else {
    load_weights(net, run.best_path);
    check_weights_digest(*net, recorded_digest(md, ModelFiles::kWeights), run.best_path, run.config_path);
    net->to(run.device);
  }
  ValidationResult v = validate_model(net, batcher, index, o, md.norm.pressure_scale_kpa, true, run.comm);
  if (o.mirror) {  // mirror averaging at inference, kept if it helps on validation
    const ValidationResult m = validate_model(net, batcher, index, o, md.norm.pressure_scale_kpa, true, run.comm, true);
    md.model.mirror = m.rmse_kpa < v.rmse_kpa;
    run.log("train: mirror averaging: val RMSE " + format_number("%.4f", v.rmse_kpa) + " -> " + format_number("%.4f", m.rmse_kpa) +
            " kPa, " + (md.model.mirror ? "kept" : "not kept"));
    if (md.model.mirror) v = m;
  }
  // The output activation threshold that best matches the truth's contact
  // area on the validation windows (the first candidate, 0.5 kPa, is the
  // binarisation threshold itself: no change to the binary maps).
  const int best_c = int(std::max_element(v.binary_r2.begin(), v.binary_r2.end()) - v.binary_r2.begin());
  md.norm.contact_threshold_kpa = o.fit_contact_threshold ? kThresholdCandidatesKpa[best_c] : 0.0;
  TrainResult result;
  result.epochs_run = s.epoch;
  result.best_epoch = s.best_epoch;
  result.best_val_loss = s.best_val;
  result.first_val_loss = s.first_val;
  result.val_rmse_kpa = v.rmse_kpa;
  result.stopped_early = s.bad_epochs >= o.patience;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  const CommStats& cs = run.comm.stats();
  result.allreduce_calls = cs.calls;
  result.allreduce_bytes = cs.bytes;
  result.allreduce_seconds = cs.seconds;
  const double binary_r2 = v.binary_r2[std::size_t(o.fit_contact_threshold ? best_c : 0)];
  md.metrics = json{{"epochs_run", s.epoch},
                    {"best_epoch", s.best_epoch},
                    {"best_val_loss", s.best_val},
                    {"first_val_loss", s.first_val},
                    {"stopped_early", result.stopped_early},
                    {"val_rmse_kpa", v.rmse_kpa},
                    {"val_rmse_copy_kpa", v.copy_rmse_kpa},
                    {"val_rmse_weight_scale_kpa", v.scale_rmse_kpa},
                    {"val_rmse_zero_kpa", v.zero_rmse_kpa},
                    {"val_rmse_zoom_kpa", std::isfinite(v.zoom_rmse_kpa) ? json(v.zoom_rmse_kpa) : json()},
                    {"val_binary_r2_raw", v.binary_r2.front()},
                    {"val_binary_r2", binary_r2},
                    {"val_binary_r2_copy", v.copy_binary_r2},
                    {"contact_threshold_kpa", md.norm.contact_threshold_kpa},
                    {"parameters", parameter_count(*net)}};
  run.write_config();
  char line[320];
  std::snprintf(line, sizeof line,
                "train: best epoch %d, val %.6f, val RMSE %.3f kPa (copy %.3f, weight-scale %.3f, "
                "all-zero %.3f%s); binary R^2 %.3f (raw %.3f, copy %.3f) at contact threshold %.1f kPa; %.1f s",
                s.best_epoch, s.best_val, v.rmse_kpa, v.copy_rmse_kpa, v.scale_rmse_kpa, v.zero_rmse_kpa,
                std::isfinite(v.zoom_rmse_kpa) ? format_number(", body scale %.3f", v.zoom_rmse_kpa).c_str() : "",
                binary_r2, v.binary_r2.front(), v.copy_binary_r2, md.norm.contact_threshold_kpa, result.seconds);
  run.log(line);
  // A model no better than a baseline is kept, and said so (an Error with strict).
  result.warning = baseline_warning(md.metrics);
  if (!result.warning.empty() && o.strict)
    throw Error::in(run.dir.string(), result.warning + " (" + field_text("strict") + "; the folder is kept)");
  if (run.comm.distributed() && cs.calls > 0) {
    std::snprintf(line, sizeof line, "train: %d ranks, %lld all-reduces, %.3f ms and %s each on average (rank %d)",
                  run.comm.size(), (long long)cs.calls, 1e3 * cs.seconds / double(cs.calls),
                  bytes_text(std::uint64_t(cs.bytes / cs.calls)).c_str(), run.comm.rank());
    run.log(line);
  }
  return result;
}

// Distributed: the ranks must agree on the data, the windows, the epoch and
// the starting weights before the first step.
void check_ranks_agree(const TrainRun& run, const WindowIndex& index, const PressureTransferNet& net, const TrainState& s) {
  if (!run.comm.distributed()) return;
  const auto halves = [](const std::string& text) {
    const std::uint64_t h = std::hash<std::string>{}(text);
    return std::array<double, 2>{double(h >> 32), double(h & 0xffffffffu)};
  };
  json options = options_json(run.o);
  options.erase("threads");  // hosts may differ in cores
  const auto data = halves(run.digest + options.dump()), weights = halves(weights_digest(*net));
  run.comm.check_same({data[0], data[1], double(index.train_size()), double(index.val_size()), double(s.epoch),
                       weights[0], weights[1]},
                      "the data, the options, the resumed epoch or the starting weights");
}

}  // namespace

TrainResult train(const PressureSource& source, const std::string& out_dir, const TrainOptions& o) {
  check_options(o);
  if (o.rank == 0) check_out_dir(out_dir, o);  // before the ranks meet and the windows are indexed
  const auto t_start = std::chrono::steady_clock::now();
  // Joins the other ranks first: a bad rendezvous fails before any work.
  const auto comm = Communicator::join({o.world_size, o.rank, o.rendezvous, o.dist_timeout_s, o.dist_token});
  TrainRun run(source, out_dir, o, *comm);
  if (o.threads > 0) torch::set_num_threads(o.threads);
  plan_model(run);
  const WindowIndex index = index_windows(run);
  if (run.writes()) prepare_out_dir(out_dir, o);
  // A fresh run that fails while setting up leaves nothing behind.
  LeftoverGuard leftovers(out_dir, o.resume || !run.writes());
  PressureTransferNet net = build_network(run);
  torch::optim::Adam optimizer(net->parameters(), torch::optim::AdamOptions(o.lr));
  TrainState s = start_or_resume(run, net, optimizer);
  check_ranks_agree(run, index, net, s);
  log_setup(run, index, net, s);
  Batcher batcher(source, index, run.md.norm, o.cache_mb, run.device, run.md.model);
  leftovers.done();  // from here a failure names what it keeps (the checkpoint)
  run_epochs(run, net, optimizer, batcher, index, s);
  return final_metrics(run, net, batcher, index, s, t_start);
}

}  // namespace ptnet
