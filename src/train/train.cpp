// The training loop: batches from the lazy window index, Adam with a step
// learning-rate schedule, early stopping, atomic checkpoints, exact resume.
// With distributed.cpp, the only Torch translation units of the train stage.
//
// Dimension legend: N windows in a batch, T window frames, H x W mat cells,
// A = 3 attributes.
#include <algorithm>
#include <chrono>
#include <exception>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <sstream>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/model.hpp"
#include "ptnet/zip_check.hpp"
#include "ptnet/train.hpp"
#include "distributed.hpp"
#include "window_index.hpp"

namespace ptnet {
namespace fs = std::filesystem;
using nlohmann::json;

TrainOptions TrainOptions::from_preset(const std::string& name) {
  TrainOptions o;
  o.preset = name;
  if (name == "paper") {  // the defaults are the paper's
    o.threads = 2;        // 1.8x faster than 1 thread with the 64/128/256 widths (bench_model)
    return o;
  }
  if (name == "fast" || name == "full") {
    // Measured: docs/model.md, docs/results.md (the frame network against the
    // residual window network and the body-scale baseline).
    o.model = ModelConfig::fast();
    o.model.arch = Arch::frame;
    o.model.align = Align::zoom;
    o.model.window = 1;            // the network works per frame: a window is one frame
    o.model.channels = {16, 32, 48};
    o.model.hidden = 64;           // the FiLM MLP
    o.model.contact = true;        // a contact head: binary R^2 0.855 -> 0.908 on validation (docs/results.md)
    o.contact_weight = 0.05;
    o.epochs = 12;
    o.batch = 64;
    o.lr = 3e-3;
    o.lr_halve_every = 4;
    o.threads = 1;  // measured on this 2-core machine: bench_model
    o.patience = 10;
    o.stride = 1;
    o.samples_per_epoch = 8192;
    o.val_samples = 4096;
    o.crop_rows = 40;              // half the mat around the feet
    o.cache_mb = 3072;             // the embedded dataset's 1.7 GB of frames stay decoded
    if (name == "full") {          // the same network trained 5x longer (docs/results.md)
      o.epochs = 30;
      o.samples_per_epoch = 16384;
      o.val_samples = 8192;
      o.lr_halve_every = 8;
      o.mirror = true;             // corpus unseen 0.852 -> 0.833 x body scale (docs/results.md)
    }
    return o;
  }
  throw Error("--preset: expected paper, fast or full, found \"" + name + "\"");
}

void TrainOptions::set_arch(Arch arch) {
  model.arch = arch;
  if (arch == Arch::frame) return;
  model.window = kWindowFrames;
  model.contact = false;
  contact_weight = 0;
}

std::string TrainOptions::summary() const {
  std::ostringstream s;
  s << arch_name(model.arch) << " " << model.channels[0] << "/" << model.channels[1] << "/" << model.channels[2]
    << " on " << (model.align == Align::zoom ? "body-scale aligned" : "recorded") << " input, window "
    << model.window << ", batch " << batch << ", Adam lr " << lr << " halved every " << lr_halve_every
    << " epochs, " << epochs << " epochs of ";
  if (samples_per_epoch > 0) s << samples_per_epoch << " windows";
  else s << "every window";
  if (crop_rows > 0) s << " (" << crop_rows << "-row crops)";
  if (model.contact) s << ", contact head (cross-entropy weight " << contact_weight << ")";
  if (mirror) s << ", mirrored windows";
  s << ", patience " << patience << ", " << threads << " thread" << (threads == 1 ? "" : "s");
  return s.str();
}

namespace {

const char* loss_name(Loss l) { return l == Loss::mse_force ? "mse+force" : "mse"; }

json options_json(const TrainOptions& o) {
  return json{{"preset", o.preset},        {"epochs", o.epochs},
              {"batch", o.batch},          {"micro_batch", o.micro_batch},
              {"lr", o.lr},
              {"lr_halve_every", o.lr_halve_every}, {"patience", o.patience},
              {"seed", o.seed},            {"threads", o.threads},
              {"device", o.device},        {"stride", o.stride},
              {"samples_per_epoch", o.samples_per_epoch}, {"val_samples", o.val_samples},
              {"loss", loss_name(o.loss)}, {"force_weight", o.force_weight},
              {"contact_weight", o.contact_weight},
              {"init", o.init},            {"val_fraction", 0.1},
              {"fit_contact_threshold", o.fit_contact_threshold},
              {"identity_pairs", o.identity_pairs}, {"crop_rows", o.crop_rows}, {"mirror", o.mirror},
              {"world_size", o.world_size}};
}

void check_options(const TrainOptions& o) {
  auto at_least = [](const char* what, double v, double min) {
    if (!(v >= min)) {
      std::ostringstream s;
      s << "--" << what << ": must be >= " << min << ", found " << v;
      throw Error(s.str());
    }
  };
  at_least("epochs", o.epochs, 1);
  at_least("batch", o.batch, 1);
  at_least("micro-batch", o.micro_batch, 1);
  at_least("patience", o.patience, 1);
  at_least("stride", o.stride, 1);
  at_least("threads", o.threads, 0);
  if (o.threads > max_threads())
    throw Error("--threads: must be <= " + std::to_string(max_threads()) + ", found " + std::to_string(o.threads));
  at_least("lr-halve-every", o.lr_halve_every, 1);
  at_least("samples-per-epoch", double(o.samples_per_epoch), 0);
  at_least("val-samples", double(o.val_samples), 0);
  at_least("crop-rows", o.crop_rows, 0);
  at_least("contact-weight", o.contact_weight, 0);
  if (!(o.lr > 0 && std::isfinite(o.lr))) throw Error("--lr: must be > 0");
}

double lr_at(const TrainOptions& o, int epoch0) {  // epoch0: 0-based
  return o.lr * std::pow(0.5, epoch0 / o.lr_halve_every);
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

struct Batch {
  torch::Tensor x, y, sa, ta;  // network input, truth [N,T,H,W]; attributes [N,A], [N,A]
  torch::Tensor src;           // the source windows as recorded [N,T,H,W] (= x unless aligned)
};

class Batcher {
 public:
  Batcher(const PressureSource& src, const WindowIndex& index, const Normalisation& norm,
          double cache_mb, torch::Device device, Align align)
      : source_(src), index_(index), cache_(src, cache_mb), device_(device),
        inv_scale_(float(1.0 / norm.pressure_scale_kpa)), align_(align) {
    for (const auto& s : src.sequences()) attrs_.push_back(norm.attributes(src.body(s.body_id)));
  }

  // with_source: also keep the unaligned source windows (for the baselines).
  Batch load(const std::vector<WindowRef>& refs, bool with_source = false) {
    const int n = int(refs.size()), t = index_.options().window;
    const MatSpec m = source_.mat();
    const std::int64_t per = std::int64_t(t) * m.cells();
    Batch b;
    b.x = torch::empty({n, t, m.rows, m.cols}, torch::kFloat32);
    b.y = torch::empty({n, t, m.rows, m.cols}, torch::kFloat32);
    b.sa = torch::empty({n, kAttributes}, torch::kFloat32);
    b.ta = torch::empty({n, kAttributes}, torch::kFloat32);
    float *x = b.x.data_ptr<float>(), *y = b.y.data_ptr<float>();
    float *sa = b.sa.data_ptr<float>(), *ta = b.ta.data_ptr<float>();
    // Aligned input: the recorded source windows go to b.src (kept for the
    // baselines) or a scratch window, and their zoom to b.x.
    const bool aligned = align_ == Align::zoom;
    if (aligned && with_source) b.src = torch::empty_like(b.x);
    std::vector<float> scratch(aligned && !with_source ? std::size_t(per) : 0);
    for (int i = 0; i < n; ++i) {
      const Pair& p = index_.pairs()[std::size_t(refs[i].pair)];
      if (aligned) {
        float* recorded = with_source ? b.src.data_ptr<float>() + i * per : scratch.data();
        cache_.read(p.source, refs[i].start, t, recorded);
        const BodySpec& a = body_of(p.source);
        const BodySpec& z = body_of(p.target);
        zoom_frames(recorded, x + i * per, t, m.rows, m.cols, body_scale(a.height_cm, z.height_cm),
                    body_gain(a.height_cm, a.weight_kg, z.height_cm, z.weight_kg));
      } else {
        cache_.read(p.source, refs[i].start, t, x + i * per);
      }
      cache_.read(p.target, refs[i].start, t, y + i * per);
      std::copy_n(attrs_[std::size_t(p.source)].data(), kAttributes, sa + i * kAttributes);
      std::copy_n(attrs_[std::size_t(p.target)].data(), kAttributes, ta + i * kAttributes);
    }
    b.x.mul_(inv_scale_);
    b.y.mul_(inv_scale_);
    if (aligned && with_source) b.src.mul_(inv_scale_);
    else b.src = b.x;
    if (device_ != torch::kCPU) {
      b.x = b.x.to(device_), b.y = b.y.to(device_), b.sa = b.sa.to(device_), b.ta = b.ta.to(device_);
      b.src = b.src.to(device_);
    }
    return b;
  }

  // Windows per source attribute ratio (for the weight-scale baseline).
  double weight_ratio(const WindowRef& r) const {
    const auto& seqs = source_.sequences();
    const Pair& p = index_.pairs()[std::size_t(r.pair)];
    return source_.body(seqs[p.target].body_id).weight_kg / source_.body(seqs[p.source].body_id).weight_kg;
  }

 private:
  const PressureSource& source_;
  const WindowIndex& index_;
  SequenceCache cache_;
  torch::Device device_;
  float inv_scale_;
  Align align_;
  std::vector<std::array<float, 3>> attrs_;
  const BodySpec& body_of(int seq) const { return source_.body(source_.sequences()[std::size_t(seq)].body_id); }
};

// Training crops for a fully convolutional network (Arch::frame): each
// window cut to `rows` mat rows centred on its pressure (input and truth), so
// that the work goes where the feet are. b.x, b.y [N,T,H,W] -> [N,T,rows,W].
void crop_to_pressure(Batch& b, int rows) {
  const auto n = b.x.size(0), h = b.x.size(2);
  if (rows >= h) return;
  auto profile = (b.x + b.y).sum({1, 3});                                   // [N,H]
  auto mass = profile.sum(1);                                               // [N]
  auto centre = (profile * torch::arange(h, profile.options())).sum(1) / mass.clamp_min(1e-12);
  const torch::Tensor centre_cpu = centre.cpu(), mass_cpu = mass.cpu();
  const auto centres = centre_cpu.accessor<float, 1>();
  const auto masses = mass_cpu.accessor<float, 1>();
  std::vector<torch::Tensor> xs, ys;
  for (int64_t i = 0; i < n; ++i) {
    const double c = masses[i] > 0 ? double(centres[i]) : 0.5 * double(h);
    const int64_t r0 = std::clamp<int64_t>(std::llround(c - 0.5 * rows), 0, h - rows);
    xs.push_back(b.x[i].narrow(1, r0, rows));
    ys.push_back(b.y[i].narrow(1, r0, rows));
  }
  b.x = torch::stack(xs);
  b.y = torch::stack(ys);
}

// TrainOptions::mirror: windows 1, 3, 5, ... of a micro-batch (the epoch's
// order is shuffled) mirrored through the mat's long axis, input and truth.
void mirror_every_second(Batch& b) {
  using torch::indexing::None;
  using torch::indexing::Slice;
  const auto odd = Slice(1, None, 2);
  for (torch::Tensor* t : {&b.x, &b.y}) {
    torch::Tensor out = t->clone();
    out.index_put_({odd}, t->index({odd}).flip({-1}));
    *t = out;
  }
}

// Content loss (MSE) on the output ReLU(raw), except that cells whose truth
// is > 0 use the raw value: their gradient never dies (see forward_raw).
// Equal to the MSE of the output wherever raw >= 0 or truth == 0. With a
// contact head, plus contact_weight x the cross-entropy of its logits against
// the truth's contact (> 0).
torch::Tensor loss_fn(const TrainOptions& o, const PressureTransferNetImpl::Raw& raw, const torch::Tensor& truth) {
  auto out = torch::where(truth > 0, raw.pressure, torch::relu(raw.pressure));
  auto loss = torch::mse_loss(out, truth);
  if (o.loss == Loss::mse_force) {
    // Relative error of the total force of each frame, squared.
    auto f_out = out.sum({2, 3}), f_truth = truth.sum({2, 3});
    loss = loss + o.force_weight * ((f_out - f_truth) / (f_truth + 1.0)).pow(2).mean();
  }
  if (raw.contact.defined())
    loss = loss + o.contact_weight * torch::binary_cross_entropy_with_logits(raw.contact, (truth > 0).to(raw.contact.dtype()));
  return loss;
}

// Candidate output activation thresholds (kPa) for the contact fit.
constexpr double kThresholdCandidatesKpa[] = {0.5, 1, 1.5, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40};
constexpr int kCandidates = int(std::size(kThresholdCandidatesKpa));

struct ValResult {
  double mse = 0;                       // normalised
  double rmse_kpa = 0, copy_rmse_kpa = 0, scale_rmse_kpa = 0, zero_rmse_kpa = 0;
  double zoom_rmse_kpa = NAN;           // the aligned (zoomed) source, when the model aligns
  // With baselines: binary R^2 (cells > kContactKpa) of the output zeroed
  // below each candidate threshold, and of the copy baseline.
  std::vector<double> binary_r2;        // [kCandidates]
  double copy_binary_r2 = 0;
};

// Distributed: the micro-batches are dealt round-robin to the ranks and the
// sums all-reduced, so every rank gets the whole validation set's result.
// `mirrored`: the network's output averaged as at inference with ModelConfig::mirror.
ValResult validate_model(PressureTransferNet& net, Batcher& batcher, const WindowIndex& index,
                         const TrainOptions& o, double scale_kpa, bool baselines, Communicator& comm,
                         bool mirrored = false) {
  const std::int64_t total = index.val_size();
  const std::int64_t n = o.val_samples > 0 ? std::min(o.val_samples, total) : total;
  net->eval();
  torch::NoGradGuard no_grad;
  double sum = 0, copy_sum = 0, scale_sum = 0, zero_sum = 0, zoom_sum = 0;
  const bool aligned = net->config().align == Align::zoom;
  double ones = 0, copy_mismatches = 0;
  std::vector<double> mismatches(kCandidates, 0.0);
  std::int64_t count = 0;
  std::vector<WindowRef> refs;
  std::int64_t chunk = 0;  // micro-batches so far
  auto flush = [&]() {
    if (refs.empty()) return;
    if (chunk++ % comm.size() != comm.rank()) {
      refs.clear();
      return;
    }
    Batch b = batcher.load(refs, baselines);
    const auto forward = [&](const torch::Tensor& x) { return net->forward(x, b.sa, b.ta); };
    auto out = mirrored ? mirror_averaged(forward, b.x) : forward(b.x);
    sum += torch::mse_loss(out, b.y, torch::Reduction::Sum).item<double>();
    if (baselines) {
      copy_sum += torch::mse_loss(b.src, b.y, torch::Reduction::Sum).item<double>();
      zero_sum += b.y.pow(2).sum().item<double>();
      if (aligned) zoom_sum += torch::mse_loss(b.x, b.y, torch::Reduction::Sum).item<double>();
      std::vector<float> ratio;
      for (const auto& r : refs) ratio.push_back(float(batcher.weight_ratio(r)));
      auto k = torch::tensor(ratio).view({-1, 1, 1, 1}).to(b.x.device());
      scale_sum += torch::mse_loss(b.src * k, b.y, torch::Reduction::Sum).item<double>();
      const auto contact = b.y * float(scale_kpa) > kContactKpa;     // [N,T,H,W] bool
      const auto out_kpa = out * float(scale_kpa);
      ones += contact.sum().item<double>();
      copy_mismatches += ((b.src * float(scale_kpa) > kContactKpa) != contact).sum().item<double>();
      for (int c = 0; c < kCandidates; ++c) {
        const double t = std::max(kThresholdCandidatesKpa[c], kContactKpa);
        mismatches[std::size_t(c)] += ((out_kpa >= t) != contact).sum().item<double>();
      }
    }
    count += out.numel();
    refs.clear();
  };
  for (std::int64_t i = 0; i < n; ++i) {
    refs.push_back(index.val(n == total ? i : i * total / n));
    if (int(refs.size()) == std::min(o.batch, o.micro_batch)) flush();
  }
  flush();
  std::vector<double> sums{sum, copy_sum, scale_sum, zero_sum, zoom_sum, ones, copy_mismatches, double(count)};
  sums.insert(sums.end(), mismatches.begin(), mismatches.end());
  comm.allreduce(sums, "the validation all-reduce");
  sum = sums[0], copy_sum = sums[1], scale_sum = sums[2], zero_sum = sums[3], zoom_sum = sums[4];
  ones = sums[5], copy_mismatches = sums[6], count = std::int64_t(sums[7]);
  std::copy(sums.begin() + 8, sums.end(), mismatches.begin());
  ValResult r;
  r.mse = sum / double(count);
  r.rmse_kpa = std::sqrt(r.mse) * scale_kpa;
  r.copy_rmse_kpa = std::sqrt(copy_sum / double(count)) * scale_kpa;
  r.scale_rmse_kpa = std::sqrt(scale_sum / double(count)) * scale_kpa;
  r.zero_rmse_kpa = std::sqrt(zero_sum / double(count)) * scale_kpa;
  r.zoom_rmse_kpa = aligned ? std::sqrt(zoom_sum / double(count)) * scale_kpa : NAN;
  if (baselines) {
    for (double m : mismatches) r.binary_r2.push_back(binary_r2_from_counts(m, ones, double(count)));
    r.copy_binary_r2 = binary_r2_from_counts(copy_mismatches, ones, double(count));
  }
  return r;
}

// Training windows of one epoch: all (shuffled) or `samples_per_epoch` drawn
// uniformly, from a generator seeded by (seed, epoch) so resume matches.
std::vector<std::int64_t> epoch_order(const TrainOptions& o, const WindowIndex& index, int epoch0) {
  std::mt19937_64 rng(o.seed * 0x9E3779B97F4A7C15ull + std::uint64_t(epoch0) + 1);
  const std::int64_t total = index.train_size();
  std::vector<std::int64_t> order;
  if (o.samples_per_epoch > 0 && o.samples_per_epoch < total) {
    std::uniform_int_distribution<std::int64_t> pick(0, total - 1);
    for (std::int64_t i = 0; i < o.samples_per_epoch; ++i) order.push_back(pick(rng));
  } else {
    order.resize(std::size_t(total));
    for (std::int64_t i = 0; i < total; ++i) order[std::size_t(i)] = i;
    for (std::int64_t i = total - 1; i > 0; --i) {
      std::uniform_int_distribution<std::int64_t> pick(0, i);
      std::swap(order[std::size_t(i)], order[std::size_t(pick(rng))]);
    }
  }
  return order;
}

struct State {
  int epoch = 0;  // epochs completed
  double best_val = INFINITY, first_val = 0;
  int best_epoch = 0, bad_epochs = 0;
  std::string history = "epoch,train_loss,val_loss,lr,seconds\n";
};

void save_checkpoint(const std::string& path, const PressureTransferNet& net, torch::optim::Adam& opt,
                     const State& s) {
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

State load_checkpoint(const std::string& path, PressureTransferNet& net, torch::optim::Adam& opt) {
  if (!fs::exists(path)) throw Error::in(path, "no checkpoint to resume from");
  verify_zip_file(path);
  torch::serialize::InputArchive archive, model, optim;
  State s;
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

void prepare_out_dir(const std::string& dir, const TrainOptions& o) {
  std::error_code ec;
  if (o.resume) {
    if (!fs::is_directory(dir, ec)) throw Error::in(dir, "no model folder to resume");
    return;
  }
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw Error::in(dir, "exists and is not a folder");
    const bool empty = fs::is_empty(dir, ec);
    if (!empty && !o.force) throw Error::in(dir, "exists; pass --force to overwrite or --resume to continue");
    for (const char* f : {"config.json", "model.pt", "checkpoint.pt", "history.csv"})
      fs::remove(fs::path(dir) / f, ec);
  } else {
    fs::path parent = fs::path(dir).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
      throw Error::in(dir, "folder " + parent.string() + " does not exist");
    if (!fs::create_directory(dir, ec)) throw Error::in(dir, "cannot create folder: " + ec.message());
  }
}

// Removes what a fresh run wrote when it fails while setting up (before the
// first epoch starts: bad --init weights, memory, data): config.json,
// checkpoint.pt, history.csv and the folder if it is then empty. Failures in
// the epochs keep the last checkpoint and say so; a resumed run is left as is.
class LeftoverGuard {
 public:
  LeftoverGuard(std::string dir, bool resume) : dir_(std::move(dir)), active_(!resume) {}
  ~LeftoverGuard() {
    if (!active_ || std::uncaught_exceptions() == 0) return;
    std::error_code ec;
    if (fs::exists(fs::path(dir_) / "model.pt", ec)) return;
    for (const char* f : {"config.json", "checkpoint.pt", "history.csv"}) fs::remove(fs::path(dir_) / f, ec);
    if (fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
  }
  void done() { active_ = false; }

 private:
  std::string dir_;
  bool active_;
};

// ---- the phases of train(), in order

// What the phases share: the model folder's files and what goes into config.json.
struct Run {
  const PressureSource& source;
  TrainOptions o;  // a copy: plan_model settles contact_weight
  fs::path dir;
  std::string config_path, ckpt_path, best_path;
  torch::Device device;
  ModelDir md;        // written to config.json
  ModelDir previous;  // --resume: the folder's config; --init: the other model's
  std::string digest;
  Communicator& comm;  // the ranks (a world of one when not distributed)
  // Distributed: the best weights so far, kept by the ranks that do not
  // write the folder (they may not see rank 0's model.pt).
  std::vector<torch::Tensor> best_snapshot;

  Run(const PressureSource& src, const std::string& out_dir, const TrainOptions& options, Communicator& c)
      : source(src), o(options), dir(out_dir), config_path((dir / "config.json").string()),
        ckpt_path((dir / "checkpoint.pt").string()), best_path((dir / "model.pt").string()),
        device(parse_device(options.device)), comm(c) {}
  bool writes() const { return comm.rank() == 0; }  // rank 0 alone writes the model folder
  void log(const std::string& line) const {
    if (o.progress) o.progress(progress_line("train", line));
  }
  void write_config() {
    if (writes()) write_text_file(config_path, to_json(md).dump(2) + "\n", /*force=*/true);
  }
};

// Parameters and buffers, in a fixed order (the best-weights snapshot).
std::vector<torch::Tensor> weight_tensors(const PressureTransferNet& net) {
  std::vector<torch::Tensor> out;
  for (const auto& p : net->parameters()) out.push_back(p);
  for (const auto& b : net->buffers()) out.push_back(b);
  return out;
}

// The architecture from the options, the resumed folder or the --init model,
// checked against the data's mat and frame rate and the available memory.
void plan_model(Run& run) {
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
    throw Error("--contact-weight: a model with a contact head needs a weight > 0");
  if (!md.model.contact) o.contact_weight = 0;
  if ((o.resume || !o.init.empty()) && std::abs(previous.fps - source.fps()) > 1e-6 * previous.fps)
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
WindowIndex index_windows(Run& run) {
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
PressureTransferNet build_network(const Run& run) {
  const TrainOptions& o = run.o;
  torch::manual_seed(o.seed);
  PressureTransferNet net(run.md.model);
  if (run.md.model.contact) net->set_contact_floor(run.md.norm.min_reading_kpa / run.md.norm.pressure_scale_kpa);
  if (!o.init.empty() && !o.resume) {
    const std::string init_weights = (fs::path(o.init) / "model.pt").string();
    load_weights(net, init_weights);
    check_weights_digest(*net, recorded_digest(run.previous, "model.pt"), init_weights,
                         (fs::path(o.init) / "config.json").string());
  }
  net->to(run.device);
  return net;
}

// --resume: the checkpoint's state (its weights checked against config.json);
// a fresh run: the initial weights as the epoch-0 checkpoint.
State start_or_resume(Run& run, PressureTransferNet& net, torch::optim::Adam& optimizer) {
  State s;
  if (run.o.resume) {
    s = load_checkpoint(run.ckpt_path, net, optimizer);
    int recorded_epoch = -1;
    const std::string recorded = recorded_digest(run.previous, "checkpoint.pt", &recorded_epoch);
    // A kill between the checkpoint's rename and config.json's leaves the
    // config one epoch behind: that checkpoint passed its CRCs and is taken.
    if (recorded_epoch != s.epoch - 1) check_weights_digest(*net, recorded, run.ckpt_path, run.config_path);
  } else if (run.writes()) {
    save_checkpoint(run.ckpt_path, net, optimizer, s);  // epoch 0: the initial weights
    record_digest(run.md, "checkpoint.pt", weights_digest(*net), 0);
    run.write_config();
  }
  return s;
}

void log_setup(const Run& run, const WindowIndex& index, const PressureTransferNet& net, const State& s) {
  const ModelConfig& m = run.md.model;
  run.log("train: " + std::to_string(index.pairs().size()) + " pairs, " + std::to_string(index.train_size()) +
          " training / " + std::to_string(index.val_size()) + " validation windows, " +
          std::to_string(parameter_count(*net)) + " parameters (" + arch_name(m.arch) + " " +
          std::to_string(m.channels[0]) + "/" + std::to_string(m.channels[1]) + "/" +
          std::to_string(m.channels[2]) + "), pressure scale " + fmt("%.3g", run.md.norm.pressure_scale_kpa) +
          " kPa, " + std::to_string(torch::get_num_threads()) + " threads" +
          (run.comm.distributed() ? ", " + std::to_string(run.comm.size()) + " ranks" : "") +
          (run.o.resume ? ", resuming after epoch " + std::to_string(s.epoch) : ""));
  const int micro_batches = (run.o.batch + run.o.micro_batch - 1) / run.o.micro_batch;
  if (run.comm.size() > micro_batches)
    run.log("train: warning: " + std::to_string(micro_batches) + " micro-batch(es) per step for " +
            std::to_string(run.comm.size()) + " ranks: some ranks idle (set --micro-batch to at most --batch / ranks)");
}

// BatchNorm running statistics of a step whose micro-batches are spread over
// the ranks. One process updates them micro-batch after micro-batch:
// r <- (1 - a) r + a x_m, so after M of them r = (1 - a)^M r0 + sum_m
// (1 - a)^(M-1-m) a x_m. Each rank runs its micro-batches from zeroed
// buffers (the update is then a x_m), adds them up with that decay, and the
// sum over the ranks (all-reduced with the gradients) completes the formula.
class SharedBatchNorm {
 public:
  explicit SharedBatchNorm(torch::nn::Module& net) {
    for (const auto& m : net.modules(/*include_self=*/false))
      if (auto* bn = dynamic_cast<torch::nn::BatchNorm2dImpl*>(m.get()); bn && bn->options.track_running_stats())
        layers_.push_back(bn);
  }
  void begin_step() {
    start_.clear();
    sums_.clear();
    for (auto* bn : layers_) {
      start_.push_back({bn->running_mean.clone(), bn->running_var.clone(), bn->num_batches_tracked.clone()});
      sums_.push_back(torch::zeros_like(bn->running_mean));
      sums_.push_back(torch::zeros_like(bn->running_var));
    }
  }
  void before_micro_batch() {
    torch::NoGradGuard no_grad;
    for (auto* bn : layers_) bn->running_mean.zero_(), bn->running_var.zero_();
  }
  void after_micro_batch(int m, int count) {
    torch::NoGradGuard no_grad;
    for (std::size_t i = 0; i < layers_.size(); ++i) {
      const double decay = std::pow(1 - momentum(i), count - 1 - m);
      sums_[2 * i].add_(layers_[i]->running_mean, decay);
      sums_[2 * i + 1].add_(layers_[i]->running_var, decay);
    }
  }
  std::vector<torch::Tensor>& sums() { return sums_; }  // all-reduced by the caller
  void end_step(int count) {
    torch::NoGradGuard no_grad;
    for (std::size_t i = 0; i < layers_.size(); ++i) {
      const double decay = std::pow(1 - momentum(i), count);
      layers_[i]->running_mean.copy_(start_[i][0] * decay + sums_[2 * i]);
      layers_[i]->running_var.copy_(start_[i][1] * decay + sums_[2 * i + 1]);
      layers_[i]->num_batches_tracked.copy_(start_[i][2] + count);
    }
  }

 private:
  double momentum(std::size_t i) const { return layers_[i]->options.momentum().value_or(0.1); }
  std::vector<torch::nn::BatchNorm2dImpl*> layers_;
  std::vector<std::array<torch::Tensor, 3>> start_;
  std::vector<torch::Tensor> sums_;
};

// One epoch of optimiser steps (epoch0 0-based); the mean training loss.
// Distributed: each rank runs the micro-batches m with m % ranks == rank;
// the gradients (each micro-batch's loss already weighted by its share of
// the whole batch), the BatchNorm statistics and the loss are summed over
// the ranks before the step.
double train_epoch(const Run& run, PressureTransferNet& net, torch::optim::Adam& optimizer, Batcher& batcher,
                   const WindowIndex& index, int epoch0, const State& s) {
  const TrainOptions& o = run.o;
  Communicator& comm = run.comm;
  SharedBatchNorm shared_bn(*net);
  const std::vector<torch::Tensor> params = net->parameters();
  net->train();
  const auto order = epoch_order(o, index, epoch0);
  double loss_sum = 0;
  std::int64_t seen = 0;
  std::vector<WindowRef> refs;
  for (std::size_t i = 0; i < order.size(); i += std::size_t(o.batch)) {
    refs.clear();
    for (std::size_t j = i; j < std::min(order.size(), i + std::size_t(o.batch)); ++j)
      refs.push_back(index.train(order[j]));
    // One optimiser step per batch; gradients accumulate over micro-batches,
    // each loss weighted by its share of the batch (= the batch mean).
    optimizer.zero_grad();
    double l = 0;
    const std::size_t micro = std::size_t(std::max(1, o.micro_batch));
    const int micro_batches = int((refs.size() + micro - 1) / micro);
    if (comm.distributed()) shared_bn.begin_step();
    for (std::size_t m = 0; m < refs.size(); m += micro) {
      const int k = int(m / micro);
      if (k % comm.size() != comm.rank()) continue;
      const std::vector<WindowRef> part(refs.begin() + std::ptrdiff_t(m),
                                        refs.begin() + std::ptrdiff_t(std::min(refs.size(), m + micro)));
      if (comm.distributed()) shared_bn.before_micro_batch();
      Batch b = batcher.load(part);
      if (o.crop_rows > 0 && run.md.model.arch == Arch::frame) crop_to_pressure(b, o.crop_rows);
      if (o.mirror) mirror_every_second(b);
      auto loss = loss_fn(o, net->forward_parts(b.x, b.sa, b.ta), b.y) * (double(part.size()) / double(refs.size()));
      const double part_loss = loss.item<double>();
      if (!std::isfinite(part_loss))
        throw Error("training diverged: loss is " + std::string(std::isnan(part_loss) ? "NaN" : "infinite") +
                    " at epoch " + std::to_string(epoch0 + 1) + ", batch " + std::to_string(i / o.batch + 1) +
                    " (try a lower --lr); the last good checkpoint (epoch " + std::to_string(s.epoch) +
                    ") is kept in " + run.ckpt_path);
      loss.backward();
      l += part_loss;
      if (comm.distributed()) shared_bn.after_micro_batch(k, micro_batches);
    }
    if (comm.distributed()) {
      std::vector<torch::Tensor> summed;
      for (const auto& p : params) {
        if (!p.grad().defined()) p.mutable_grad() = torch::zeros_like(p);
        summed.push_back(p.grad());
      }
      for (const auto& t : shared_bn.sums()) summed.push_back(t);
      summed.push_back(torch::tensor(float(l)));
      comm.allreduce(summed, "the gradient all-reduce (epoch " + std::to_string(epoch0 + 1) + ")");
      shared_bn.end_step(micro_batches);
      l = double(summed.back().item<float>());
    }
    optimizer.step();
    loss_sum += l * double(refs.size());
    seen += std::int64_t(refs.size());
    if (o.progress) {
      Progress p = progress_count("train", seen, std::int64_t(order.size()), "windows");
      p.step = epoch0 + 1;
      p.steps = o.epochs;
      o.progress(p);
    }
  }
  return loss_sum / double(seen);
}

// After an epoch: the best weights when validation improved, the history,
// the checkpoint and config.json; the epoch's log line.
void record_epoch(Run& run, PressureTransferNet& net, torch::optim::Adam& optimizer, State& s, int epoch0,
                  double train_loss, double val_loss, double lr, double secs) {
  s.epoch = epoch0 + 1;
  if (epoch0 == 0) s.first_val = val_loss;
  if (val_loss < s.best_val) {
    s.best_val = val_loss;
    s.best_epoch = epoch0 + 1;
    s.bad_epochs = 0;
    if (run.writes()) {
      save_weights(net, run.best_path);
      record_digest(run.md, "model.pt", weights_digest(*net));
      run.write_config();
    } else {
      run.best_snapshot.clear();
      for (const auto& t : weight_tensors(net)) run.best_snapshot.push_back(t.detach().clone());
    }
  } else {
    ++s.bad_epochs;
  }
  s.history += std::to_string(epoch0 + 1) + "," + fmt("%.6g", train_loss) + "," + fmt("%.6g", val_loss) + "," +
               fmt("%.6g", lr) + "," + fmt("%.3f", secs) + "\n";
  if (run.writes()) {
    save_checkpoint(run.ckpt_path, net, optimizer, s);
    record_digest(run.md, "checkpoint.pt", weights_digest(*net), s.epoch);
    run.write_config();
    write_text_file((run.dir / "history.csv").string(), s.history, /*force=*/true);
  }
  char line[160];
  std::snprintf(line, sizeof line, "[epoch %d/%d] train %.6f val %.6f lr %.1e %.1f s", epoch0 + 1, run.o.epochs,
                train_loss, val_loss, lr, secs);
  run.log(line);
}

// The epochs, until the last one or early stopping.
void run_epochs(Run& run, PressureTransferNet& net, torch::optim::Adam& optimizer, Batcher& batcher,
                const WindowIndex& index, State& s) {
  const TrainOptions& o = run.o;
  const bool finished_before = s.epoch >= o.epochs || s.bad_epochs >= o.patience;
  for (int e = s.epoch; e < o.epochs && s.bad_epochs < o.patience && !finished_before; ++e) {
    const auto t0 = std::chrono::steady_clock::now();
    const double lr = lr_at(o, e);
    for (auto& group : optimizer.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
    const double train_loss = train_epoch(run, net, optimizer, batcher, index, e, s);
    const ValResult v = validate_model(net, batcher, index, o, run.md.norm.pressure_scale_kpa, false, run.comm);
    if (!std::isfinite(v.mse))
      throw Error("training diverged: validation loss is not finite at epoch " + std::to_string(e + 1) +
                  "; the last good checkpoint (epoch " + std::to_string(s.epoch) + ") is kept in " + run.ckpt_path);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    record_epoch(run, net, optimizer, s, e, train_loss, v.mse, lr, secs);
  }
}

// The best weights on the validation windows: RMSE beside the baselines,
// binary R^2, the fitted contact threshold; into config.json and the result.
TrainResult final_metrics(Run& run, PressureTransferNet& net, Batcher& batcher, const WindowIndex& index,
                          const State& s, std::chrono::steady_clock::time_point t_start) {
  const TrainOptions& o = run.o;
  ModelDir& md = run.md;
  if (!run.best_snapshot.empty()) {  // a rank that does not write: its copy of the best weights
    torch::NoGradGuard no_grad;
    const auto tensors = weight_tensors(net);
    for (std::size_t i = 0; i < tensors.size(); ++i) tensors[i].copy_(run.best_snapshot[i]);
  } else {
    load_weights(net, run.best_path);
    check_weights_digest(*net, recorded_digest(md, "model.pt"), run.best_path, run.config_path);
    net->to(run.device);
  }
  ValResult v = validate_model(net, batcher, index, o, md.norm.pressure_scale_kpa, true, run.comm);
  if (o.mirror) {  // mirror averaging at inference, kept if it helps on validation
    const ValResult m = validate_model(net, batcher, index, o, md.norm.pressure_scale_kpa, true, run.comm, true);
    md.model.mirror = m.rmse_kpa < v.rmse_kpa;
    run.log("train: mirror averaging: val RMSE " + fmt("%.4f", v.rmse_kpa) + " -> " + fmt("%.4f", m.rmse_kpa) +
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
                std::isfinite(v.zoom_rmse_kpa) ? fmt(", body scale %.3f", v.zoom_rmse_kpa).c_str() : "",
                binary_r2, v.binary_r2.front(), v.copy_binary_r2, md.norm.contact_threshold_kpa, result.seconds);
  run.log(line);
  if (run.comm.distributed() && cs.calls > 0) {
    std::snprintf(line, sizeof line, "train: %d ranks, %lld all-reduces, %.3f ms and %s each on average (rank %d)",
                  run.comm.size(), (long long)cs.calls, 1e3 * cs.seconds / double(cs.calls),
                  bytes_text(std::uint64_t(cs.bytes / cs.calls)).c_str(), run.comm.rank());
    run.log(line);
  }
  return result;
}

}  // namespace

// Distributed: the ranks must agree on the data, the windows, the epoch and
// the starting weights before the first step.
void check_ranks_agree(const Run& run, const WindowIndex& index, const PressureTransferNet& net, const State& s) {
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

TrainResult train(const PressureSource& source, const std::string& out_dir, const TrainOptions& o) {
  check_options(o);
  const auto t_start = std::chrono::steady_clock::now();
  // Joins the other ranks first: a bad rendezvous fails before any work.
  const auto comm = Communicator::join({o.world_size, o.rank, o.rendezvous, o.dist_timeout_s});
  Run run(source, out_dir, o, *comm);
  if (o.threads > 0) torch::set_num_threads(o.threads);
  plan_model(run);
  const WindowIndex index = index_windows(run);
  if (run.writes()) prepare_out_dir(out_dir, o);
  // A fresh run that fails while setting up leaves nothing behind.
  LeftoverGuard leftovers(out_dir, o.resume || !run.writes());
  PressureTransferNet net = build_network(run);
  torch::optim::Adam optimizer(net->parameters(), torch::optim::AdamOptions(o.lr));
  State s = start_or_resume(run, net, optimizer);
  check_ranks_agree(run, index, net, s);
  log_setup(run, index, net, s);
  Batcher batcher(source, index, run.md.norm, o.cache_mb, run.device, run.md.model.align);
  leftovers.done();  // from here a failure names what it keeps (the checkpoint)
  run_epochs(run, net, optimizer, batcher, index, s);
  return final_metrics(run, net, batcher, index, s, t_start);
}

}  // namespace ptnet
