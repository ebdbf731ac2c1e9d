// ptnet evaluate: the paper's Table 2 for a trained model on a dataset.
//
//   ptnet evaluate --model model/ --data data.h5 [--threshold 0.5] [--out report/]
//
// Test pairs: ordered pairs of two different `original` bodies on the same
// motion; seen = take-1 motions, unseen = take-2. Prints the Markdown table and
// writes report/metrics.{csv,json}, qualitative.png and one GIF per category.
#include <iostream>

#include "command.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/transfer.hpp"

namespace ptnet::cli {
namespace {

struct EvaluateCli {
  std::string model, data, out = "report";
  double threshold_kpa = 0.5;
  int stride = 5, threads = 0;
  bool force = false, raw = false;
};

void run(const EvaluateCli& c) {
  if (!(c.threshold_kpa >= 0)) throw Error("--threshold: expected a non-negative kPa value");
  const Dataset dataset = Dataset::open(c.data);
  TransferOptions to;
  to.stride = c.stride;
  to.raw = c.raw;
  to.threads = c.threads;
  const Transfer net(c.model, to);
  const TransferFn model = [&](const PressureSequence& s, const BodySpec& a, const BodySpec& b) {
    return net.run(s, a, b);
  };
  EvaluateOptions eo;
  eo.metrics.threshold_kpa = c.threshold_kpa;
  const bool quiet = globals().quiet;
  eo.progress = [quiet](int done, int total) {
    if (!quiet && (done == total || done % 10 == 0))
      std::cerr << "evaluate: " << done << "/" << total << " pairs\r" << (done == total ? "\n" : "")
                << std::flush;
  };
  const auto rows = evaluate_pairs(dataset, model, eo);
  ReportOptions ro;
  ro.out_dir = c.out;
  ro.force = c.force;
  ro.threshold_kpa = c.threshold_kpa;
  const auto written = write_report(dataset, rows, model, ro);
  std::cout << format_table(rows) << "\n";
  std::cout << "Paper (Table 2): seen RMSE 8.88, binary R^2 0.79; unseen RMSE 12.82, binary R^2 0.70\n";
  for (const auto& p : written) std::cout << "wrote " << p << "\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<EvaluateCli>();
  auto* cmd = app.add_subcommand("evaluate", "Table 2: RMSE and binary R^2 of a model on original bodies");
  cmd->add_option("--model", c->model, "Model directory (ptnet train --out)")->required();
  cmd->add_option("--data", c->data, "Dataset (.h5) with at least two 'original' bodies")->required();
  cmd->add_option("--threshold", c->threshold_kpa, "Binarisation threshold for binary R^2 and IoU (kPa)")
      ->capture_default_str();
  cmd->add_option("--out", c->out, "Report folder")->capture_default_str();
  cmd->add_option("--stride", c->stride, "Frames between transfer windows (averaged)")->capture_default_str();
  cmd->add_option("--threads", c->threads, "Torch threads (0: default)")->capture_default_str();
  cmd->add_flag("--raw", c->raw, "Raw network output: skip the model's fitted contact threshold");
  cmd->add_flag("--force", c->force, "Overwrite existing report files");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(80, setup);
}  // namespace ptnet::cli
