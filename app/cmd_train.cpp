// ptnet train: trains PressureTransferNet on a dataset file into a model folder.
//
//   ptnet train --data data.h5 --out model/ --preset fast
//   ptnet train --data data.h5 --out model/ --resume            # continue
//   ptnet train --data finetune.h5 --out tuned/ --init model/ --identity-pairs   # fine-tune
//   ptnet train --data data.h5 --out model/ --nproc 2                # 2 local ranks (docs/distributed.md)
//   ptnet train ... --world-size 4 --rank 1 --rendezvous tcp://node1:29500
#include <cstdint>
#include <limits>

#include "command.hpp"
#include "local_ranks.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/train.hpp"

namespace ptnet::cli {
namespace {

struct TrainCli {
  std::string data, out, preset = "paper", device = "cpu", arch, align, channels, loss, init;
  int epochs = 0, batch = 0, micro_batch = 0, patience = 0, threads = -1, stride = 0, hidden = 0, latent = 0;
  int window = 0, context = -1, crop_rows = -1;
  double contact_weight = -1;
  int lr_halve_every = 0;
  long long samples_per_epoch = -1, val_samples = -1;
  double lr = 0, cache_mb = 0;
  long long seed = -1;
  bool resume = false, force = false, no_contact_threshold = false, identity_pairs = false;
  int nproc = 0, world_size = 1, rank = 0;
  std::string rendezvous, mirror;
  double dist_timeout_s = 60;
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
  if (!ok) throw Error("--channels: expected three comma-separated widths like 16,32,64, found \"" + text + "\"");
  return c;
}

void run(const TrainCli& c) {
  if (c.nproc > 0 && (c.world_size != 1 || c.rank != 0 || !c.rendezvous.empty()))
    throw Error("--nproc starts its own ranks; it excludes --world-size, --rank and --rendezvous");
  if (c.nproc > 1) {
    run_local_ranks(c.nproc, /*grace_s=*/c.dist_timeout_s);
    return;
  }
  TrainOptions o = TrainOptions::from_preset(c.preset);
  if (c.epochs) o.epochs = c.epochs;
  if (c.batch) o.batch = c.batch;
  if (c.micro_batch) o.micro_batch = c.micro_batch;
  if (c.lr) o.lr = c.lr;
  if (c.lr_halve_every) o.lr_halve_every = c.lr_halve_every;
  if (c.patience) o.patience = c.patience;
  if (c.seed >= 0) o.seed = std::uint64_t(c.seed);
  if (c.threads >= 0) o.threads = c.threads;
  if (c.stride) o.stride = c.stride;
  if (c.samples_per_epoch >= 0) o.samples_per_epoch = c.samples_per_epoch;
  if (c.val_samples >= 0) o.val_samples = c.val_samples;
  if (c.cache_mb > 0) o.cache_mb = c.cache_mb;
  if (!c.arch.empty()) o.set_arch(parse_arch(c.arch));  // --window below may still set the window
  if (!c.align.empty()) o.model.align = parse_align(c.align);
  if (!c.channels.empty()) o.model.channels = parse_channels(c.channels);
  if (c.hidden) o.model.hidden = c.hidden;
  if (c.latent) o.model.latent = c.latent;
  if (c.window) o.model.window = c.window;
  if (c.context >= 0) o.model.context = c.context;
  if (c.contact_weight >= 0) o.contact_weight = c.contact_weight;
  o.model.contact = o.contact_weight > 0;
  if (c.crop_rows >= 0) o.crop_rows = c.crop_rows;
  if (!c.mirror.empty()) o.mirror = c.mirror == "on";
  if (!c.loss.empty()) {
    if (c.loss == "mse") o.loss = Loss::mse;
    else if (c.loss == "mse+force") o.loss = Loss::mse_force;
    else throw Error("--loss: expected mse or mse+force, found \"" + c.loss + "\"");
  }
  o.device = c.device;
  o.init = c.init;
  o.identity_pairs = c.identity_pairs;
  o.resume = c.resume;
  o.fit_contact_threshold = !c.no_contact_threshold;
  o.force = c.force;
  o.world_size = c.world_size;
  o.rank = c.rank;
  o.rendezvous = c.rendezvous;
  o.dist_timeout_s = c.dist_timeout_s;
  if (c.rank == 0) o.progress = train_progress();  // the other ranks report errors only
  if (o.resume && !o.init.empty()) throw Error("--resume and --init exclude each other");
  auto source = open_dataset_source(c.data);
  train(*source, c.out, o);
}

void setup(CLI::App& app) {
  auto opt = std::make_shared<TrainCli>();
  auto* cmd = app.add_subcommand(
      "train",
      "Train PressureTransferNet on a dataset (pairs of the same motion on two retargeted bodies,\n"
      "take-1 motions; original bodies and take-2 motions are never used) into a model folder:\n"
      "config.json, model.pt (best weights), checkpoint.pt, history.csv. One line per epoch on stderr\n"
      "(on a terminal also a progress line inside each epoch: windows, windows/s, ETA).\n"
      "Presets:\n  paper = the paper's: " + TrainOptions::from_preset("paper").summary() +
      "\n  fast  = ours: " + TrainOptions::from_preset("fast").summary() +
      "\n  full  = ours, longer: " + TrainOptions::from_preset("full").summary() +
      "\nOptions left out keep the preset's value.");
  cmd->add_option("--data", opt->data, "Dataset file (HDF5, ptnet simulate)")->required();
  cmd->add_option("--out", opt->out, "Model folder to create")->required();
  cmd->add_option("--preset", opt->preset, "paper | fast | full")->capture_default_str();
  cmd->add_option("--epochs", opt->epochs, "Maximum epochs")->check(CLI::Range(1, 1000000));
  cmd->add_option("--batch", opt->batch, "Windows per optimiser step")->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--micro-batch", opt->micro_batch,
                  "Windows per forward/backward pass (gradients accumulated up to --batch; default 64)")
      ->check(CLI::Range(1, 1 << 20));
  cmd->add_option("--lr", opt->lr, "Initial Adam learning rate")->check(positive(10));
  cmd->add_option("--lr-halve-every", opt->lr_halve_every, "Epochs between learning-rate halvings")->check(CLI::Range(1, 1000000));
  cmd->add_option("--patience", opt->patience, "Early stop after this many epochs without improvement")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--seed", opt->seed, "Seed of weights, sampling and split (default 1)")
      ->check(CLI::Range(0LL, (1LL << 62)));
  cmd->add_option("--threads", opt->threads, "CPU threads (paper 2, fast 1: measured, see bench_model; 0: LibTorch default)")
      ->check(thread_count(true));
  cmd->add_option("--device", opt->device, "cpu | cuda")->capture_default_str();
  cmd->add_option("--stride", opt->stride, "Frames between window starts")->check(CLI::Range(1, 100000));
  cmd->add_option("--samples-per-epoch", opt->samples_per_epoch, "Training windows per epoch (0 = all)")
      ->check(CLI::Range(0LL, 1LL << 40));
  cmd->add_option("--val-samples", opt->val_samples, "Validation windows (0 = all)")->check(CLI::Range(0LL, 1LL << 40));
  cmd->add_option("--arch", opt->arch,
                  "faithful (the paper's) | skip (U-Net skip connections) | residual (skip, learns a correction "
                  "to the source) | frame (per-frame conditional U-Net with FiLM at every scale, a correction)");
  cmd->add_option("--align", opt->align,
                  "none (the paper's) | zoom (input aligned to the target body: zoomed by the height ratio "
                  "about the mat centre, scaled by weight over area ratio)");
  cmd->add_option("--channels", opt->channels, "Conv widths of the three blocks, e.g. 64,128,256");
  cmd->add_option("--hidden", opt->hidden, "Width of the FC layer after the convolutions (128)")
      ->check(CLI::Range(1, 1 << 16));
  cmd->add_option("--latent", opt->latent, "Latent width (128)")->check(CLI::Range(1, 1 << 16));
  cmd->add_option("--window", opt->window, "Frames per window (the paper's 30; --arch frame works per frame: 1)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--context", opt->context, "--arch frame: neighbouring frames on each side as input (0)")
      ->check(CLI::Range(0, 16));
  cmd->add_option("--crop-rows", opt->crop_rows,
                  "--arch frame: train on this many mat rows around the pressure (0 = whole mat)")
      ->check(CLI::Range(0, 1 << 24));
  cmd->add_option("--mirror", opt->mirror,
                  "on | off: train on left-right mirrored windows too and keep mirror averaging "
                  "at inference if it lowers the validation RMSE (the full preset: on)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--contact-weight", opt->contact_weight,
                  "--arch frame: weight of the contact head's cross-entropy (0 = no contact head)")
      ->check(CLI::Range(0.0, 1e6));
  cmd->add_option("--loss", opt->loss, "mse (the paper's content loss) | mse+force (adds total-force error)");
  cmd->add_option("--cache-mb", opt->cache_mb, "Budget of the whole-sequence cache (default 1024)")
      ->check(positive(1e7));
  cmd->add_flag("--no-contact-threshold", opt->no_contact_threshold,
                "Do not fit the output activation threshold (raw network output, as in the paper)");
  cmd->add_flag("--resume", opt->resume, "Continue from OUT/checkpoint.pt");
  cmd->add_option("--init", opt->init, "Start from this model folder's weights (fine-tuning)");
  cmd->add_flag("--identity-pairs", opt->identity_pairs,
                "A motion recorded on one body only trains as the pair (body -> same body): for "
                "fine-tuning on real recordings (ptnet import --dataset ... --subjects ...)");
  cmd->add_flag("--force", opt->force, "Overwrite an existing model folder");
  cmd->add_option("--nproc", opt->nproc,
                  "Start this many ranks on this machine (127.0.0.1, a free port) and wait for them; "
                  "progress from rank 0 (docs/distributed.md)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--world-size", opt->world_size, "Ranks of a distributed run (default 1)")
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--rank", opt->rank, "This process's rank, 0 .. world size - 1 (rank 0 writes the model folder)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--rendezvous", opt->rendezvous,
                  "tcp://HOST:PORT (rank 0 listens on PORT of HOST) or file://PATH (a fresh file on a shared "
                  "filesystem)");
  cmd->add_option("--dist-timeout", opt->dist_timeout_s,
                  "Seconds any rank waits for the others (joining, each all-reduce) before failing (default 60)")
      ->check(in_range(0.1, 86400));
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace

PTNET_COMMAND(50, setup);

}  // namespace ptnet::cli
