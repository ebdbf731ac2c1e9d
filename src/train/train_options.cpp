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

}  // namespace

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
  auto at_least = [](const char* what, double v, double min) {
    if (!(v >= min)) {
      std::ostringstream s;
      s << field_text(what) << ": must be >= " << min << ", found " << v;
      throw Error(s.str());
    }
  };
  at_least("epochs", o.epochs, 1);
  at_least("batch", o.batch, 1);
  at_least("micro_batch", o.micro_batch, 1);
  at_least("patience", o.patience, 1);
  at_least("stride", o.stride, 1);
  at_least("threads", o.threads, 0);
  if (o.threads > max_threads())
    throw Error(field_text("threads") + ": must be <= " + std::to_string(max_threads()) +
                ", found " + std::to_string(o.threads));
  at_least("lr_halve_every", o.lr_halve_every, 1);
  at_least("samples_per_epoch", double(o.samples_per_epoch), 0);
  at_least("val_samples", double(o.val_samples), 0);
  at_least("crop_rows", o.crop_rows, 0);
  at_least("contact_weight", o.contact_weight, 0);
  if (!(o.lr > 0 && std::isfinite(o.lr))) throw Error(field_text("lr") + ": must be > 0");
}

double lr_at(const TrainOptions& o, int epoch0) {  // epoch0: 0-based
  return o.lr * std::pow(0.5, epoch0 / o.lr_halve_every);
}

}  // namespace ptnet
