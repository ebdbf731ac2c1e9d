// ptnet demo: the embedded default, no external data. Procedural motions
// (performers x 4 categories x 2 takes) retargeted onto 8 + 8 sampled bodies and
// 2 + 2 held-out original bodies, simulated on the 80 x 28 mat, written as a
// dataset with a figure of one motion on two bodies. Every output stays in the
// folder so each later step (train, evaluate, render) can be rerun on it.
#include <filesystem>
#include <iostream>

#include "command.hpp"
#include "ptnet/body.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/viz.hpp"

namespace ptnet::cli {
namespace {

struct DemoCli {
  std::string out = "demo";
  int performers = 5, takes = 2, threads = 0;
  double seconds = 8;
  std::uint64_t seed = 1;
  bool force = false;
};

void run(const DemoCli& c) {
  namespace fs = std::filesystem;
  const bool quiet = globals().quiet;
  fs::create_directories(c.out);
  const std::string data_path = (fs::path(c.out) / "data.h5").string();
  const std::string bodies_path = (fs::path(c.out) / "bodies.csv").string();
  const std::string figure_path = (fs::path(c.out) / "walking_two_bodies.png").string();
  for (const auto& p : {data_path, bodies_path, figure_path}) check_output_path(p, c.force);

  const auto bodies = sample_bodies(8, 8, 2, 2, c.seed);
  write_text_file(bodies_path, format_bodies_csv(bodies), c.force);
  std::vector<Body> built;
  for (const auto& b : bodies) built.emplace_back(b);

  struct Clip { Motion motion; SequenceMeta meta; };
  std::vector<Clip> clips;
  for (int p = 1; p <= c.performers; ++p)
    for (Category cat : kCategories)
      for (int take = 1; take <= c.takes; ++take) {
        GenerateOptions g;
        g.category = cat;
        g.performer = p;
        g.take = take;
        g.seconds = c.seconds;
        g.seed = c.seed;
        Clip clip{generate_motion(g), {}};
        clip.meta.motion_id = "p" + std::to_string(p) + "_" + category_name(cat) + "_t" + std::to_string(take);
        clip.meta.performer = "P" + std::to_string(p);
        clip.meta.category = category_name(cat);
        clip.meta.take = take;
        clip.meta.source = "procedural:" + clip.meta.motion_id;
        clips.push_back(std::move(clip));
      }
  if (!quiet) std::cerr << "demo: " << clips.size() << " procedural clips on " << bodies.size() << " bodies\n";

  std::vector<Motion> retargeted;
  std::vector<SimJob> jobs;
  std::vector<SequenceMeta> metas;
  retargeted.reserve(clips.size() * bodies.size());
  for (const auto& clip : clips)
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      retargeted.push_back(retarget(clip.motion, bodies[b].height_cm));
      SequenceMeta m = clip.meta;
      m.body_id = bodies[b].id;
      m.name = m.motion_id + "__" + m.body_id;
      metas.push_back(m);
    }
  SimOptions so;
  so.seed = c.seed;
  for (std::size_t i = 0; i < retargeted.size(); ++i)
    jobs.push_back({&retargeted[i], &built[i % bodies.size()], sequence_seed(c.seed, metas[i].name)});
  const auto sequences = simulate_many(jobs, so, c.threads, [quiet](int done, int total) {
    if (!quiet && (done % 50 == 0 || done == total))
      std::cerr << "simulate: " << done << "/" << total << " sequences\r" << (done == total ? "\n" : "") << std::flush;
  });

  DatasetInfo info;
  info.mat = so.mat;
  info.fps = 30;
  info.generator = std::string("ptnet ") + PTNET_VERSION + " demo";
  info.config_json = "{\"performers\": " + std::to_string(c.performers) + ", \"takes\": " +
                     std::to_string(c.takes) + ", \"seconds\": " + std::to_string(c.seconds) +
                     ", \"seed\": " + std::to_string(c.seed) + "}";
  {
    DatasetWriter w(data_path, info, bodies, c.force);
    for (std::size_t i = 0; i < sequences.size(); ++i) w.add(metas[i], sequences[i]);
    w.commit();
  }
  const Dataset d = Dataset::open(data_path);
  const std::string motion = "p1_walking_t1";
  FigureOptions fo;
  fo.cop = true;
  render_figure(d, {motion + "__" + bodies.front().id, motion + "__" + bodies[8].id}, figure_path, fo, c.force);
  std::cout << describe_dataset(d, false) << "\n";
  std::cout << "wrote " << bodies_path << "\nwrote " << data_path << "\nwrote " << figure_path << "\n"
            << "next: ptnet train --data " << data_path << " --out " << c.out << "/model --preset fast\n"
            << "      ptnet evaluate --model " << c.out << "/model --data " << data_path << " --out " << c.out
            << "/report\n";
}

void setup(CLI::App& app) {
  auto c = std::make_shared<DemoCli>();
  auto* cmd = app.add_subcommand("demo", "The embedded default: procedural motions, bodies, simulation, figure");
  cmd->add_option("--out", c->out, "Output folder")->capture_default_str();
  cmd->add_option("--performers", c->performers, "Procedural performers")->capture_default_str()->check(CLI::Range(1, 50));
  cmd->add_option("--takes", c->takes, "Takes per performer and category")->capture_default_str()->check(CLI::Range(1, 5));
  cmd->add_option("--seconds", c->seconds, "Seconds per clip")->capture_default_str()->check(CLI::Range(2.0, 120.0));
  cmd->add_option("--seed", c->seed, "Seed")->capture_default_str();
  cmd->add_option("--threads", c->threads, "Simulation threads (0: all cores)")->capture_default_str();
  cmd->add_flag("--force", c->force, "Overwrite existing outputs");
  cmd->callback([c] { run(*c); });
}

}  // namespace
PTNET_COMMAND(90, setup);
}  // namespace ptnet::cli
