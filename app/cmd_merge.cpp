// ptnet merge: the shards of `ptnet simulate --shard K/N` into one dataset.
//
//   ptnet simulate ... --shard 0/2 --out part0.h5      # on one host
//   ptnet simulate ... --shard 1/2 --out part1.h5      # on another
//   ptnet merge part0.h5 part1.h5 --out all.h5         # = the unsharded run
#include <iostream>

#include "command.hpp"
#include "ptnet/data.hpp"

namespace ptnet::cli::cmd_merge {
namespace {

struct MergeCli {
  std::vector<std::string> inputs;
  std::string out;
  bool force = false;
};

void run(const MergeCli& c) {
  const int sequences = merge_datasets(c.inputs, c.out, c.force);
  if (!globals().quiet)
    std::cerr << "merge: " << c.inputs.size() << " files, " << sequences << " sequences\n";
  std::cout << "wrote " << c.out << "\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<MergeCli>();
  auto* cmd = app.add_subcommand(
      "merge",
      "Merge the shards of one `ptnet simulate --shard K/N` run (all N, any order) into one dataset:\n"
      "the unsharded run's sequences, attributes and bodies (docs/distributed.md). Inputs must share\n"
      "mat, fps, generator, bodies and config; a sequence in two inputs is an error.");
  cmd->add_option("inputs", c->inputs, "Dataset files (.h5)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", c->out, "Output dataset (.h5)")->required();
  cmd->add_flag("-f,--force", c->force, "Overwrite the output if it exists");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(45, setup);
}  // namespace ptnet::cli::cmd_merge
