// ptnet motions: procedural motion clips, or one clip read from a motion
// file (--from), as BVH on the canonical skeleton.
//
//   ptnet motions --category walking --performer 2 --take 1 --seconds 10 --out walk.bvh
//   ptnet motions --performers 5 --takes 2 --out-dir clips/      # + clips/clips.csv
//   ptnet motions --from trial.trc --static static.trc --out trial.bvh   # a file's canonical joints
//
// One clip, or a whole set (every performer x category x take) with a
// clips.csv manifest (file,subject,category,take; subject = performer).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::cli::cmd_motions {
namespace {

struct MotionsCli {
  // One clip.
  std::string category;
  int performer = 1;
  int take = 1;
  std::string out;
  // A set.
  int performers = 0;
  int takes = 1;
  std::string categories = "walking,rom,freestyle,acting";
  std::string out_dir;
  // Both.
  double seconds = 10;
  double fps = kFps;
  std::uint64_t seed = 0;
  double height_cm = 0;
  bool force = false;
  // A clip read from a file (BVH or markers) instead of generated.
  std::string from, static_markers, marker_map, units = "auto";
};

std::vector<Category> parse_categories(const std::string& list) {
  std::vector<Category> out;
  std::vector<std::string> names;
  for (const std::string& item : split_list(list)) {
    out.push_back(parse_category(item));
    names.push_back(category_name(out.back()));
  }
  if (out.empty()) throw Error("--categories: expected a comma-separated list of categories, found '" + list + "'");
  if (const std::string twice = first_repeat(names); !twice.empty())
    throw Error("--categories: " + twice + " given twice");
  return out;
}

GenerateOptions generate_options(const MotionsCli& o, Category c, int performer, int take) {
  GenerateOptions g;
  g.category = c;
  g.performer = performer;
  g.take = take;
  g.seconds = o.seconds;
  g.fps = o.fps;
  g.seed = o.seed;
  g.height_cm = o.height_cm;
  return g;
}

void progress(const std::string& line) {
  if (!globals().quiet) std::cerr << line << "\n";
}

void run_one(const MotionsCli& o) {
  const Category c = parse_category(o.category);
  check_bvh_output(o.out, o.force);
  const Motion m = generate_motion(generate_options(o, c, o.performer, o.take));
  write_bvh(motion_to_bvh(m), o.out, o.force);
  char height[32];
  std::snprintf(height, sizeof height, "%.1f", o.height_cm > 0 ? o.height_cm : performer_height_cm(o.performer, o.seed));
  progress("[motions] " + o.out + ": " + category_name(c) + ", performer " + std::to_string(o.performer) + " (" +
           height + " cm), take " + std::to_string(o.take) + ", " + std::to_string(m.size()) + " frames");
}

// A motion file (BVH or .trc markers) on the canonical skeleton, as BVH: a
// marker trial's joints for any BVH viewer.
void run_from(const MotionsCli& o) {
  check_bvh_output(o.out, o.force);
  MotionOptions mo;
  mo.fps = o.fps;
  mo.static_markers = o.static_markers;
  mo.marker_map = o.marker_map;
  mo.units = parse_units(o.units);
  const Motion m = load_motion(o.from, mo);
  write_bvh(motion_to_bvh(m), o.out, o.force);
  progress("[motions] " + o.out + ": " + o.from + " on the canonical skeleton, " + std::to_string(m.size()) +
           " frames at " + number_text(m.fps) + " fps");
}

void run_set(const MotionsCli& o) {
  namespace fs = std::filesystem;
  const std::vector<Category> categories = parse_categories(o.categories);
  struct Clip {
    std::string file;
    Category category;
    int performer, take;
  };
  std::vector<Clip> clips;
  for (int p = 1; p <= o.performers; ++p)
    for (Category c : categories)
      for (int t = 1; t <= o.takes; ++t)
        clips.push_back({ptnet::motion_id(p, c, t) + ".bvh", c, p, t});
  // Refuse before creating or writing anything.
  const std::string manifest = (fs::path(o.out_dir) / "clips.csv").string();
  std::vector<std::string> files{"clips.csv"};
  for (const Clip& clip : clips) files.push_back(clip.file);
  check_outputs_in_folder(o.out_dir, files, o.force);
  make_folder(o.out_dir);

  std::string csv = "file,subject,category,take\n";
  for (std::size_t i = 0; i < clips.size(); ++i) {
    const Clip& clip = clips[i];
    const Motion m = generate_motion(generate_options(o, clip.category, clip.performer, clip.take));
    write_bvh(motion_to_bvh(m), (fs::path(o.out_dir) / clip.file).string(), o.force);
    csv += clip.file + "," + std::to_string(clip.performer) + "," + category_name(clip.category) + "," +
           std::to_string(clip.take) + "\n";
    progress("[motions " + std::to_string(i + 1) + "/" + std::to_string(clips.size()) + "] " + clip.file + " " +
             std::to_string(m.size()) + " frames");
  }
  write_text_file(manifest, csv, o.force);
  progress("[motions] " + manifest + ": " + std::to_string(clips.size()) + " clips");
}

void setup(CLI::App& app) {
  auto opt = std::make_shared<MotionsCli>();
  CLI::App* cmd = app.add_subcommand(
      "motions", "Generate procedural motion clips (walking, rom, freestyle, acting), or convert one motion file\n"
      "(--from: BVH or markers .trc), as BVH on the canonical skeleton");
  auto* category = cmd->add_option("--category", opt->category, "One clip: walking|rom|freestyle|acting")
                       ->check(CLI::IsMember({"walking", "rom", "freestyle", "acting"}));
  auto* performer = cmd->add_option("--performer", opt->performer, "One clip: performer (1..), sets style and height")
                        ->capture_default_str()->check(CLI::Range(1, 1000000));
  auto* take = cmd->add_option("--take", opt->take, "One clip: take (1..), varies the sequence")
                   ->capture_default_str()->check(CLI::Range(1, 1000000));
  auto* out = cmd->add_option("--out", opt->out, "One clip: output .bvh file");
  auto* performers = cmd->add_option("--performers", opt->performers, "A set: performers 1..N")
                         ->check(CLI::Range(1, 10000));
  auto* takes = cmd->add_option("--takes", opt->takes, "A set: takes per performer and category")
                    ->capture_default_str()->check(CLI::Range(1, 1000));
  auto* categories = cmd->add_option("--categories", opt->categories, "A set: comma-separated categories")
                         ->capture_default_str();
  auto* out_dir = cmd->add_option("--out-dir", opt->out_dir, "A set: output folder (one BVH per clip + clips.csv)");
  auto* seconds = cmd->add_option("--seconds", opt->seconds, "Clip length (s)")->capture_default_str()->check(in_range(0.1, 3600));
  cmd->add_option("--fps", opt->fps, "Frame rate (Hz)")->capture_default_str()->check(in_range(kFpsRange));
  auto* seed = cmd->add_option("--seed", opt->seed, "Seed, mixed with performer and take")->capture_default_str();
  auto* height = cmd->add_option("--height-cm", opt->height_cm, "Body height (cm); default: the performer's own")
      ->check(in_range(50, 250));
  auto* from = cmd->add_option("--from", opt->from,
                               "One clip read from a motion file (BVH, or markers .trc, .c3d) instead of generated: its\n"
                               "canonical joints as BVH (--out)");
  auto* static_markers = cmd->add_option("--static", opt->static_markers, "--from .trc: the static trial");
  auto* map = cmd->add_option("--marker-map", opt->marker_map, "--from .trc: a shipped marker map or a map file");
  auto* units = cmd->add_option("--units", opt->units,
                                 "--from: the file's unit, over a .trc's Units header or a BVH's detected one")
                    ->capture_default_str()
                    ->check(CLI::IsMember({"auto", "m", "cm", "mm", "in", "cmu"}));
  cmd->add_flag("--force", opt->force, "Overwrite existing files");
  out->excludes(out_dir);
  from->needs(out)->excludes(category)->excludes(out_dir);
  for (auto* o : {seconds, seed, height, performer, take}) from->excludes(o);  // the generator's, not a file's
  static_markers->needs(from);
  map->needs(from);
  units->needs(from);
  for (auto* o : {performers, takes, categories}) o->excludes(out)->needs(out_dir);
  for (auto* o : {category, performer, take}) o->excludes(out_dir);
  cmd->callback([opt]() {
    if (!opt->from.empty()) return run_from(*opt);
    if (opt->out.empty() && opt->out_dir.empty())
      throw CLI::RequiredError("--out (one clip) or --out-dir (a set)");
    if (!opt->out_dir.empty() && opt->performers < 1) throw CLI::RequiredError("--performers");
    if (!opt->out.empty() && opt->category.empty()) throw CLI::RequiredError("--category (or --from)");
    if (!opt->out.empty())
      run_one(*opt);
    else
      run_set(*opt);
  });
}

}  // namespace

PTNET_COMMAND(10, setup);

}  // namespace ptnet::cli::cmd_motions
