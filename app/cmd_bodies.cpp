// ptnet bodies: sample the paper's bodies into a CSV.
//
//   ptnet bodies --males 8 --females 8 --originals 2,2 --seed 1 --out bodies.csv
//   ptnet bodies --sampling cover --out bodies.csv    # retargeted bodies reach the tails
//
// Retargeted bodies: male 175 +- 15 cm, 75 +- 10 kg; female 165 +- 15 cm,
// 65 +- 10 kg (Gaussian draws, clipped to the valid ranges; or, with
// --sampling cover, a Latin hypercube over mean +- 2.5 sd); held-out
// `original` bodies (female,male counts, Gaussian) from an independent
// random stream.
#include <iostream>

#include "command.hpp"
#include "ptnet/body.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::cli::cmd_bodies {
namespace {

struct BodiesCli {
  int males = 8, females = 8;
  std::string originals = "2,2";
  std::string sampling = "paper";
  std::uint64_t seed = 1;
  std::string out;
  bool force = false;
};

void run(const BodiesCli& c) {
  check_output_name(c.out, {".csv"}, "CSV");
  check_output_path(c.out, c.force);
  const std::vector<std::string> counts = split(c.originals, ',');
  std::int64_t of = 0, om = 0;
  const auto count = [](const std::string& text, std::int64_t& n) {
    return parse_integer(text, std::int64_t(kBodyCountRange.lo), std::int64_t(kBodyCountRange.hi), n);
  };
  if (counts.size() != 2 || !count(counts[0], of) || !count(counts[1], om))
    throw Error("--originals: expected FEMALES,MALES like 2,2, each in " + kBodyCountRange.text() + ", found " +
                escaped(c.originals));
  const auto bodies = sample_bodies(c.males, c.females, int(of), int(om), c.seed, parse_body_sampling(c.sampling));
  write_text_file(c.out, format_bodies_csv(bodies), c.force);
  if (!globals().quiet) std::cerr << "bodies: wrote " << bodies.size() << " bodies to " << c.out << "\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<BodiesCli>();
  auto* cmd = app.add_subcommand("bodies", "Sample retargeted and original bodies as in the paper (CSV)");
  cmd->add_option("--males", c->males, "Retargeted male bodies")->capture_default_str()->check(int_range(kBodyCountRange));
  cmd->add_option("--females", c->females, "Retargeted female bodies")->capture_default_str()->check(int_range(kBodyCountRange));
  cmd->add_option("--originals", c->originals, "Held-out original bodies: FEMALES,MALES")->capture_default_str();
  cmd->add_option("--sampling", c->sampling,
                  "Retargeted bodies: paper (Gaussian draws) or cover (a Latin hypercube over mean +- 2.5 sd)")
      ->capture_default_str()
      ->check(CLI::IsMember({"paper", "cover"}));
  cmd->add_option("--seed", c->seed, "Seed")->capture_default_str();
  cmd->add_option("--out", c->out, "Output CSV (id,sex,height_cm,weight_kg,role)")->required();
  cmd->add_flag("--force", c->force, "Overwrite an existing file");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(30, setup);
}  // namespace ptnet::cli::cmd_bodies
