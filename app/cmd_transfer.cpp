// ptnet transfer: a recorded pressure sequence of one body -> the sequence a
// different body would have produced, with a trained model.
//
//   ptnet transfer --model model/ --in data.h5 --sequence p1_walking_t1__of01
//                  --target male,185,95 --out out.h5
//   ptnet transfer --model model/ --in rec.npy --source female,165,60
//                  --target male,185,95 --out out.npy
#include <filesystem>
#include <iostream>

#include "command.hpp"
#include "ptnet/body_spec.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/transfer.hpp"

namespace ptnet::cli::cmd_transfer {
namespace {

struct TransferCli {
  std::string model, in, sequence, source, target, out, device = TransferOptions{}.device;
  int stride = TransferOptions{}.stride, threads = TransferOptions{}.threads;
  bool force = false, raw = false;
};

// What a sequence file holds, by its extension (any case): a [T, rows,
// cols] .npy array or else a ptnet dataset; one rule for --in and --out.
enum class SequenceFile { dataset, npy };

SequenceFile sequence_file_of(const std::string& path) {
  return lower(std::filesystem::path(path).extension().string()) == ".npy" ? SequenceFile::npy : SequenceFile::dataset;
}

void run(const TransferCli& c) {
  check_output_name(c.out, {".h5", ".hdf5", ".npy"}, "a dataset or a .npy array");
  check_output_path(c.out, c.force);
  TransferOptions to;
  to.stride = c.stride;
  to.raw = c.raw;
  to.threads = c.threads;
  to.device = c.device;
  Transfer net(c.model, to);
  // Said once the output is written (an error is the run's one line).
  const auto warn = [&] { print_warning("transfer", ModelFiles(c.model).config(), baseline_warning(net.model().metrics)); };
  const BodySpec target = parse_body_attributes(c.target, "--target");
  check_body_range(target, "target body");

  PressureSequence src;
  BodySpec source;
  SequenceMeta meta;
  DatasetInfo info;
  info.mat = net.model().mat;
  info.fps = net.model().fps;
  if (sequence_file_of(c.in) == SequenceFile::npy) {
    if (c.source.empty()) throw Error("--source is required with a .npy input (e.g. --source female,165,60)");
    if (!c.sequence.empty()) throw Error("--sequence applies to a dataset input, not " + c.in);
    src = read_npy_sequence(c.in, net.model().mat, net.model().fps);
    source = parse_body_attributes(c.source, "--source");
    meta.motion_id = "npy";
  } else {
    Dataset d = Dataset::open(c.in);
    if (c.sequence.empty()) throw Error("--sequence is required with a dataset input (see ptnet info " + c.in + ")");
    meta = d.sequence(c.sequence);
    src = d.read(c.sequence);
    info.mat = d.info().mat;
    info.fps = d.info().fps;
    source = c.source.empty() ? d.body(meta.body_id) : parse_body_attributes(c.source, "--source");
  }
  check_body_range(source, "source body");
  check_output_path(c.out, c.force);  // again, now that the input is known: never the input itself
  if (!globals().quiet)
    std::cerr << "transfer: " << src.frames() << " frames, " << sex_name(source.sex) << " " << source.height_cm
              << " cm " << source.weight_kg << " kg -> " << sex_name(target.sex) << " " << target.height_cm
              << " cm " << target.weight_kg << " kg\n";
  PressureSequence out = net.run(src, source, target);
  if (sequence_file_of(c.out) == SequenceFile::npy) {
    write_npy_sequence(c.out, out, c.force);
    warn();
    return;
  }
  BodySpec body = target;
  body.id = "target";
  body.role = "transferred";
  info.generator = std::string("ptnet ") + PTNET_VERSION + " transfer";
  info.config_json = nlohmann::json{{"model", c.model}, {"input", c.in}, {"sequence", c.sequence},
                                    {"stride", c.stride}}.dump();
  SequenceMeta m = meta;
  m.name = (meta.motion_id.empty() ? std::string("sequence") : meta.motion_id) + "__target";
  m.body_id = body.id;
  m.source = "transfer:" + c.in + (c.sequence.empty() ? "" : ":" + c.sequence);
  DatasetWriter w(c.out, info, {body}, c.force);
  out.fps = info.fps;
  w.add(m, out);
  w.commit();
  warn();
}

void setup(CLI::App& app) {
  auto opt = std::make_shared<TransferCli>();
  auto* cmd = app.add_subcommand(
      "transfer",
      "Transfer a pressure sequence (at least the model's window: 30 frames for the window networks,\n"
      "1 for the frame network) from its body to a target body with a trained model: overlapping\n"
      "windows, averaged. Input: a dataset sequence (--in data.h5 --sequence NAME;\n"
      "the source body is read from the dataset) or a float32 .npy of shape [T, 80, 28] (--source\n"
      "required). Output: a one-sequence dataset (.h5) or a .npy of the same shape (kPa).");
  cmd->add_option("--model", opt->model, "Model folder (ptnet train)")->required();
  cmd->add_option("--in", opt->in, "Dataset file (.h5) or .npy [T, rows, cols] float32 kPa")->required();
  cmd->add_option("--sequence", opt->sequence, "Sequence name in the dataset");
  cmd->add_option("--source", opt->source, "Source body SEX,HEIGHT_CM,WEIGHT_KG (default: from the dataset)");
  cmd->add_option("--target", opt->target, "Target body SEX,HEIGHT_CM,WEIGHT_KG, e.g. male,185,95")->required();
  cmd->add_option("--out", opt->out, "Output .h5 or .npy")->required();
  cmd->add_option("--stride", opt->stride, "Frames between window starts (1 = every window)")
      ->capture_default_str()
      ->check(int_range(kTransferOptionsRanges.stride));
  cmd->add_option("--threads", opt->threads, "CPU threads (0 = LibTorch default)")->check(thread_count(true));
  cmd->add_option("--device", opt->device, "cpu | cuda")->capture_default_str();
  cmd->add_flag("--raw", opt->raw, "Raw network output: skip the model's fitted contact threshold");
  cmd->add_flag("--force", opt->force, "Overwrite the output");
  cmd->callback([opt]() { run(*opt); });
}

}  // namespace

PTNET_COMMAND(55, setup);

}  // namespace ptnet::cli::cmd_transfer
