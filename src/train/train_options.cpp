// TrainOptions: the presets, the summary, the checks, the learning-rate
// schedule and config.json's record of the options (train_options.hpp).
// No Torch.
#include "train_options.hpp"

#include <cmath>
#include <sstream>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
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
    // 1.5e-3: at 3e-3 some corpus runs never left body scale in 12 epochs
    // (leave-one-performer-out fold 3: 0.95 x on validation; 0.82 x at
    // 1.5e-3, seeds 1-3 within 0.01 x; the demo 0.67 -> 0.64 x).
    o.lr = 1.5e-3;
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
      o.lr = 3e-3;                 // measured at 3e-3 (docs/results.md, Table 2 on the corpus)
      o.lr_halve_every = 8;
      o.mirror = true;             // corpus unseen 0.852 -> 0.833 x body scale (docs/results.md)
    }
    return o;
  }
  throw Error(field_text("preset") + ": expected paper, fast or full, found \"" + name + "\"");
}

TrainOptions TrainOptions::from_preset(const std::string& name, const TrainOverrides& v) {
  TrainOptions o = from_preset(name);
  if (v.epochs) o.epochs = *v.epochs;
  if (v.batch) o.batch = *v.batch;
  if (v.micro_batch) o.micro_batch = *v.micro_batch;
  if (v.lr) o.lr = *v.lr;
  if (v.lr_halve_every) o.lr_halve_every = *v.lr_halve_every;
  if (v.patience) o.patience = *v.patience;
  if (v.seed) o.seed = *v.seed;
  if (v.threads) o.threads = *v.threads;
  if (v.stride) o.stride = *v.stride;
  if (v.samples_per_epoch) o.samples_per_epoch = *v.samples_per_epoch;
  if (v.val_samples) o.val_samples = *v.val_samples;
  if (v.cache_mb) o.cache_mb = *v.cache_mb;
  if (v.arch) o.set_arch(*v.arch);  // the window below may still change
  if (v.align) o.model.align = *v.align;
  if (v.channels) o.model.channels = *v.channels;
  if (v.hidden) o.model.hidden = *v.hidden;
  if (v.latent) o.model.latent = *v.latent;
  if (v.window) o.model.window = *v.window;
  if (v.context) o.model.context = *v.context;
  if (v.contact_weight) o.contact_weight = *v.contact_weight;
  o.model.contact = o.contact_weight > 0;  // the contact-head rule (check_options)
  if (v.crop_rows) o.crop_rows = *v.crop_rows;
  if (v.mirror) o.mirror = *v.mirror;
  if (v.loss) o.loss = *v.loss;
  return o;
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

const char* loss_name(Loss l) { return l == Loss::mse_force ? "mse+force" : "mse"; }

Loss parse_loss(const std::string& text) {
  if (text == "mse") return Loss::mse;
  if (text == "mse+force") return Loss::mse_force;
  throw Error(field_text("loss") + ": expected mse or mse+force, found \"" + text + "\"");
}

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
              {"init", o.init},            {"val_fraction", kValFraction},
              {"fit_contact_threshold", o.fit_contact_threshold},
              {"identity_pairs", o.identity_pairs}, {"crop_rows", o.crop_rows}, {"mirror", o.mirror},
              {"world_size", o.world_size}};
}

void check_options(const TrainOptions& o) {
  const TrainOptionsRanges& r = kTrainOptionsRanges;
  check_range("epochs", o.epochs, r.epochs);
  check_range("batch", o.batch, r.batch);
  check_range("micro_batch", o.micro_batch, r.micro_batch);
  check_range("lr", o.lr, r.lr);
  check_range("lr_halve_every", o.lr_halve_every, r.lr_halve_every);
  check_range("patience", o.patience, r.patience);
  check_range("stride", o.stride, r.stride);
  check_range("threads", o.threads, Range{0, double(max_threads())});
  check_range("samples_per_epoch", double(o.samples_per_epoch), r.samples_per_epoch);
  check_range("val_samples", double(o.val_samples), r.val_samples);
  check_range("crop_rows", o.crop_rows, r.crop_rows);
  check_range("contact_weight", o.contact_weight, r.contact_weight);
  check_range("cache_mb", o.cache_mb, r.cache_mb);
  check_range("dist_timeout_s", o.dist_timeout_s, r.dist_timeout_s);
  if (o.resume && !o.init.empty())
    throw Error(field_text("resume") + " and " + field_text("init") + " exclude each other");
  // The contact-head rule: a contact weight trains a contact head, which the
  // model must have (a resumed or --init model's own head decides: plan_model).
  if (o.contact_weight > 0 && !o.model.contact && !o.resume && o.init.empty())
    throw Error(field_text("contact_weight") + ": " + number_text(o.contact_weight) +
                " trains a contact head, which model.contact leaves out");
  if (!o.resume && o.init.empty()) validate(o.model);  // the architecture before any data is read
}

double lr_at(const TrainOptions& o, int epoch0) {  // epoch0: 0-based
  return o.lr * std::pow(0.5, epoch0 / o.lr_halve_every);
}

}  // namespace ptnet
