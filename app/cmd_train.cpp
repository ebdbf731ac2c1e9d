// ptnet train: trains PressureTransferNet on a dataset file into a model folder.
//
//   ptnet train --data data.h5 --out model/ --preset fast
//   ptnet train --data data.h5 --out model/ --resume            # continue
//   ptnet train --data finetune.h5 --out tuned/ --init model/ --identity-pairs   # fine-tune
//   ptnet train --data data.h5 --out model/ --nproc 2                # 2 local ranks (docs/distributed.md)
//   ptnet train ... --world-size 4 --rank 1 --rendezvous tcp://node1:29500
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "command.hpp"
#include "local_ranks.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/train.hpp"

namespace ptnet::cli::cmd_train {
namespace {

struct TrainCli {
  std::string data, out, preset = "paper", arch, align, channels, loss, mirror;
  TrainOverrides overrides;  // unset: the preset's value
  TrainOptions run = TrainOptions::from_preset("paper");  // device, init, resume, force, identity_pairs, ranks
  bool no_contact_threshold = false;
  int nproc = 0;
};

std::array<int, 3> parse_channels(const std::string& text) {
  const std::vector<std::string> items = split_list(text);
  std::array<int, 3> c{};
  bool ok = items.size() == c.size();
  for (std::size_t i = 0; ok && i < c.size(); ++i) {
    std::int64_t v = 0;
    ok = parse_integer(items[i], std::numeric_limits<int>::min(), std::numeric_limits<int>::max(), v);
    c[i] = int(v);
  }
  if (!ok)
    throw Error(field_text("channels") + ": expected three comma-separated widths like 16,32,64, found \"" + text +
                "\"");
  return c;
}

void run(const TrainCli& c) {
  const TrainOptions& r = c.run;
  if (c.nproc > 0 && (r.world_size != 1 || r.rank != 0 || !r.rendezvous.empty()))
    throw Error("--nproc starts its own ranks; it excludes --world-size, --rank and --rendezvous");
  if (c.nproc > 1) {
    run_local_ranks(c.nproc, /*grace_s=*/r.dist_timeout_s);
    return;
  }
  TrainOverrides v = c.overrides;
  if (!c.arch.empty()) v.arch = parse_arch(c.arch);
  if (!c.align.empty()) v.align = parse_align(c.align);
  if (!c.channels.empty()) v.channels = parse_channels(c.channels);
  if (!c.mirror.empty()) v.mirror = c.mirror == "on";
  if (!c.loss.empty()) v.loss = parse_loss(c.loss);
  TrainOptions o = TrainOptions::from_preset(c.preset, v);
  o.device = r.device;
  o.init = r.init;
  o.identity_pairs = r.identity_pairs;
  o.resume = r.resume;
  o.fit_contact_threshold = !c.no_contact_threshold;
  o.force = r.force;
  o.strict = r.strict;
  o.world_size = r.world_size;
  o.rank = r.rank;
  o.rendezvous = r.rendezvous;
  o.dist_timeout_s = r.dist_timeout_s;
  if (const char* token = std::getenv(kDistTokenVariable)) o.dist_token = token;
  if (o.rank == 0) o.progress = train_progress();  // the other ranks report errors only
  check_options(o);  // before the data is opened
  auto source = open_dataset_source(c.data);
  const TrainResult result = train(*source, c.out, o);
  if (o.rank == 0) print_warning("train", c.out, result.warning);
}

// " (paper 128, fast 64, full 64)": an option's value in each preset, for its help text.
template <class Get>
std::string preset_values(const Get& get) {
  std::string s = " (";
  for (const char* name : {"paper", "fast", "full"}) {
    std::ostringstream v;
    v << get(TrainOptions::from_preset(name));
    s += std::string(s.size() > 2 ? ", " : "") + name + " " + v.str();
  }
  return s + ")";
}

void add_schedule_options(CLI::App* cmd, TrainCli* opt);
void add_network_options(CLI::App* cmd, TrainCli* opt);
void add_run_options(CLI::App* cmd, TrainCli* opt);

void setup(CLI::App& app) {
  auto opt = std::make_shared<TrainCli>();
  auto* cmd = app.add_subcommand(
      "train",
      "Train PressureTransferNet on a dataset (pairs of the same motion on two retargeted bodies,\n"
      "take-1 motions; original bodies and take-2 motions are never used) into a model folder:\n" +
      std::string(ModelFiles::kConfig) + ", " + ModelFiles::kWeights + " (best weights), " + ModelFiles::kCheckpoint +
      ", " + ModelFiles::kHistory + ". One line per epoch on stderr\n"
      "(on a terminal also a progress line inside each epoch: windows, windows/s, ETA).\n"
      "Presets:\n  paper = the paper's: " + TrainOptions::from_preset("paper").summary() +
      "\n  fast  = ours: " + TrainOptions::from_preset("fast").summary() +
      "\n  full  = ours, longer: " + TrainOptions::from_preset("full").summary() +
      "\nOptions left out keep the preset's value.");
  cmd->add_option("--data", opt->data, "Dataset file (HDF5, ptnet simulate)")->required();
  cmd->add_option("--out", opt->out, "Model folder to create")->required();
  cmd->add_option("--preset", opt->preset, "paper | fast | full")->capture_default_str();
  add_schedule_options(cmd, opt.get());
  add_network_options(cmd, opt.get());
  add_run_options(cmd, opt.get());
  cmd->callback([opt]() { run(*opt); });
}

// Epochs, batches, learning rate, sampling, threads.
void add_schedule_options(CLI::App* cmd, TrainCli* opt) {
  TrainOverrides& v = opt->overrides;
  const TrainOptionsRanges& tr = kTrainOptionsRanges;
  cmd->add_option("--epochs", v.epochs, "Maximum epochs" + preset_values([](const TrainOptions& o) { return o.epochs; }))
      ->check(int_range(tr.epochs));
  cmd->add_option("--batch", v.batch, "Windows per optimiser step" + preset_values([](const TrainOptions& o) { return o.batch; }))
      ->check(int_range(tr.batch));
  cmd->add_option("--micro-batch", v.micro_batch,
                  "Windows per forward/backward pass, gradients accumulated up to --batch" +
                      preset_values([](const TrainOptions& o) { return o.micro_batch; }))
      ->check(int_range(tr.micro_batch));
  cmd->add_option("--lr", v.lr, "Initial Adam learning rate" + preset_values([](const TrainOptions& o) { return o.lr; }))
      ->check(in_range(tr.lr));
  cmd->add_option("--lr-halve-every", v.lr_halve_every,
                  "Epochs between learning-rate halvings" + preset_values([](const TrainOptions& o) { return o.lr_halve_every; }))
      ->check(int_range(tr.lr_halve_every));
  cmd->add_option("--patience", v.patience,
                  "Early stop after this many epochs without improvement" +
                      preset_values([](const TrainOptions& o) { return o.patience; }))
      ->check(int_range(tr.patience));
  cmd->add_option("--seed", v.seed, "Seed of weights, sampling and split" + preset_values([](const TrainOptions& o) { return o.seed; }))
      ->check(CLI::Range(0LL, (1LL << 62)));
  cmd->add_option("--threads", v.threads,
                  "CPU threads (measured: bench_model; 0: LibTorch default)" +
                      preset_values([](const TrainOptions& o) { return o.threads; }))
      ->check(thread_count(true));
  cmd->add_option("--stride", v.stride, "Frames between window starts" + preset_values([](const TrainOptions& o) { return o.stride; }))
      ->check(int_range(tr.stride));
  cmd->add_option("--samples-per-epoch", v.samples_per_epoch,
                  "Training windows per epoch, 0 = all" + preset_values([](const TrainOptions& o) { return o.samples_per_epoch; }))
      ->check(int_range(tr.samples_per_epoch));
  cmd->add_option("--val-samples", v.val_samples,
                  "Validation windows, 0 = all" + preset_values([](const TrainOptions& o) { return o.val_samples; }))
      ->check(int_range(tr.val_samples));
  cmd->add_option("--cache-mb", v.cache_mb,
                  "Budget of the whole-sequence cache" + preset_values([](const TrainOptions& o) { return o.cache_mb; }))
      ->check(in_range(tr.cache_mb));
}

// The network and its losses.
void add_network_options(CLI::App* cmd, TrainCli* opt) {
  TrainOverrides& v = opt->overrides;
  const TrainOptionsRanges& tr = kTrainOptionsRanges;
  const ModelConfigRanges& mr = kModelConfigRanges;
  cmd->add_option("--arch", opt->arch,
                  "faithful (the paper's) | skip (U-Net skip connections) | residual (skip, learns a correction "
                  "to the source) | frame (per-frame conditional U-Net with FiLM at every scale, a correction)" +
                      preset_values([](const TrainOptions& o) { return arch_name(o.model.arch); }));
  cmd->add_option("--align", opt->align,
                  "none (the paper's) | zoom (input aligned to the target body: zoomed by the height ratio "
                  "about the mat centre, scaled by weight over area ratio)" +
                      preset_values([](const TrainOptions& o) { return align_name(o.model.align); }));
  cmd->add_option("--channels", opt->channels,
                  "Conv widths of the three blocks, e.g. 64,128,256" + preset_values([](const TrainOptions& o) {
                    return std::to_string(o.model.channels[0]) + "," + std::to_string(o.model.channels[1]) + "," +
                           std::to_string(o.model.channels[2]);
                  }));
  cmd->add_option("--hidden", v.hidden,
                  "Width of the FC layer after the convolutions (the frame network: of the FiLM MLP)" +
                      preset_values([](const TrainOptions& o) { return o.model.hidden; }))
      ->check(int_range(mr.hidden));
  cmd->add_option("--latent", v.latent, "Latent width" + preset_values([](const TrainOptions& o) { return o.model.latent; }))
      ->check(int_range(mr.latent));
  cmd->add_option("--window", v.window,
                  "Frames per window (the paper's 30; --arch frame works per frame: 1)" +
                      preset_values([](const TrainOptions& o) { return o.model.window; }))
      ->check(int_range(mr.window));
  cmd->add_option("--context", v.context,
                  "--arch frame: neighbouring frames on each side as input" +
                      preset_values([](const TrainOptions& o) { return o.model.context; }))
      ->check(int_range(mr.context));
  cmd->add_option("--crop-rows", v.crop_rows,
                  "--arch frame: train on this many mat rows around the pressure, 0 = whole mat" +
                      preset_values([](const TrainOptions& o) { return o.crop_rows; }))
      ->check(int_range(tr.crop_rows));
  cmd->add_option("--mirror", opt->mirror,
                  "on | off: train on left-right mirrored windows too and keep mirror averaging "
                  "at inference if it lowers the validation RMSE" +
                      preset_values([](const TrainOptions& o) { return o.mirror ? "on" : "off"; }))
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--contact-weight", v.contact_weight,
                  "--arch frame: weight of the contact head's cross-entropy, 0 = no contact head" +
                      preset_values([](const TrainOptions& o) { return o.contact_weight; }))
      ->check(in_range(tr.contact_weight));
  cmd->add_option("--loss", opt->loss,
                  "mse (the paper's content loss) | mse+force (adds total-force error)" +
                      preset_values([](const TrainOptions& o) { return loss_name(o.loss); }));
  cmd->add_flag("--no-contact-threshold", opt->no_contact_threshold,
                "Do not fit the output activation threshold (raw network output, as in the paper)");
}

// Where the run starts from and writes, its device and its ranks.
void add_run_options(CLI::App* cmd, TrainCli* opt) {
  TrainOptions& r = opt->run;
  const TrainOptionsRanges& tr = kTrainOptionsRanges;
  cmd->add_option("--device", r.device, "cpu | cuda")->capture_default_str();
  cmd->add_flag("--resume", r.resume, "Continue from OUT/" + std::string(ModelFiles::kCheckpoint));
  cmd->add_option("--init", r.init, "Start from this model folder's weights (fine-tuning)");
  cmd->add_flag("--identity-pairs", r.identity_pairs,
                "A motion recorded on one body only trains as the pair (body -> same body): for "
                "fine-tuning on real recordings (ptnet import --dataset ... --subjects ...)");
  cmd->add_flag("--force", r.force, "Overwrite an existing model folder");
  cmd->add_flag("--strict", r.strict,
                "Exit 1 when the model is no better than the all-zero or the copy baseline on validation "
                "(the folder is kept; without it a warning line says so)");
  cmd->add_option("--nproc", opt->nproc,
                  "Start this many ranks on this machine (127.0.0.1, a free port) and wait for them; "
                  "progress from rank 0 (docs/distributed.md)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--world-size", r.world_size, "Ranks of a distributed run")->capture_default_str()
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--rank", r.rank, "This process's rank, 0 .. world size - 1 (rank 0 writes the model folder)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--rendezvous", r.rendezvous,
                  "tcp://HOST:PORT (rank 0 listens on PORT of HOST) or file://PATH (a fresh file on a shared "
                  "filesystem)");
  cmd->add_option("--dist-timeout", r.dist_timeout_s,
                  "Seconds any rank waits for the others (joining, each all-reduce) before failing")
      ->capture_default_str()->check(in_range(tr.dist_timeout_s));
}

}  // namespace

PTNET_COMMAND(50, setup);

}  // namespace ptnet::cli::cmd_train
