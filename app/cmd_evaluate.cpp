// ptnet evaluate: the paper's Table 2 for a trained model on a dataset.
//
//   ptnet evaluate --model model/ --data data.h5 [--threshold 0.5] [--out report/]
//
// Test pairs: ordered pairs of two different `original` bodies on the same
// motion; seen = take-1 motions, unseen = take-2. Prints the Markdown table and
// writes the report folder: index.html (one offline page: Table 2, charts,
// figures, training curve), metrics.{csv,json}, a PNG and a GIF per category.
#include <iostream>

#include "command.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/transfer.hpp"

namespace ptnet::cli::cmd_evaluate {
namespace {

void run(EvaluationRun r) {
  r.progress = print;
  const EvaluationResult result = run_evaluation(r);
  print_warning("evaluate", ModelFiles(r.model_dir).config(), result.warning);
  std::cout << result.table << "\n" << paper_table2_line() << "\n";
  for (const auto& p : result.written) std::cout << "wrote " << p << "\n";
  std::cout << "open " << result.page << " in a browser: the report on one page\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<EvaluationRun>();
  auto* cmd = app.add_subcommand("evaluate", "Table 2: RMSE and binary R^2 of a model on original bodies");
  cmd->add_option("--model", c->model_dir, "Model directory (ptnet train --out)")->required();
  cmd->add_option("--data", c->data_path, "Dataset (.h5) with at least two 'original' bodies")->required();
  cmd->add_option("--threshold", c->threshold_kpa, "Binarisation threshold for binary R^2 and IoU (kPa)")
      ->capture_default_str()
      ->check(in_range(kThresholdKpaRange));
  cmd->add_option("--out", c->out_dir, "Report folder")->capture_default_str();
  cmd->add_option("--stride", c->stride, "Frames between transfer windows (averaged)")
      ->capture_default_str()
      ->check(int_range(kTransferOptionsRanges.stride));
  cmd->add_option("--threads", c->threads, "Torch threads (0: default)")->capture_default_str()->check(thread_count(true));
  cmd->add_flag("--raw", c->raw, "Raw network output: skip the model's fitted contact threshold");
  cmd->add_flag("--force", c->force, "Overwrite existing report files");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(80, setup);
}  // namespace ptnet::cli::cmd_evaluate
