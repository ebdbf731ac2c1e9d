// The body-shift HAR benchmark's setup (ptnet/har_bench.hpp): body bands,
// the clips and their split in time, the transfer model's training set.
//
// Dimension legend: T frames.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "bench_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::har {

const std::vector<BodyBand>& body_bands() {
  // Stature (cm) and BMI (kg/m^2). mid: the recorded population (adults
  // near the middle of both sexes' distributions); the deployment bands lie
  // outside it in size, build or both (xshort-heavy and xtall-light: size
  // and build against each other, the stature of xsmall / xlarge with the
  // other's BMI); all covers every band.
  static const std::vector<BodyBand> bands = {
      {"mid", 160, 178, 20, 25},          {"small", 145, 157, 17, 19.5},
      {"large", 182, 198, 27, 32},        {"xsmall", 136, 146, 16, 18},
      {"xlarge", 192, 204, 30, 35},       {"short-light", 152, 159, 18.5, 20},
      {"tall-heavy", 179, 186, 25, 27.5}, {"light", 160, 178, 16.5, 19},
      {"heavy", 160, 178, 27, 33},        {"short", 145, 157, 20, 25},
      {"tall", 182, 198, 20, 25},         {"xshort-heavy", 136, 146, 30, 35},
      {"xtall-light", 192, 204, 16, 18},  {"all", 134, 206, 16, 35}};
  return bands;
}

const BodyBand& body_band(const std::string& name) {
  std::vector<std::string> names;
  for (const BodyBand& b : body_bands()) {
    if (b.name == name) return b;
    names.push_back(b.name);
  }
  throw Error("har-bench: unknown body band '" + name + "' (bands: " + join(names) + ")");
}

std::vector<std::string> deployment_band_names() {
  std::vector<std::string> names;
  for (const BodyBand& b : body_bands())
    if (b.name != "mid" && b.name != "all") names.push_back(b.name);
  return names;
}

std::vector<BodySpec> band_bodies(const BodyBand& band, int count, std::uint64_t seed, const std::string& prefix,
                                  const std::string& role) {
  if (count < 1) throw Error("har-bench: a band needs at least 1 body, found " + std::to_string(count));
  // A Latin hypercube over stature and BMI (body_spec.hpp).
  std::mt19937_64 rng(sequence_seed(seed, band.name + "/" + prefix));
  const std::vector<std::array<double, 2>> points = latin_hypercube(count, rng);
  std::vector<BodySpec> out;
  for (int i = 0; i < count; ++i) {
    BodySpec b;
    b.id = prefix + std::to_string(i + 1);
    b.sex = i % 2 == 0 ? Sex::female : Sex::male;
    const double u = points[std::size_t(i)][0], v = points[std::size_t(i)][1];
    b.height_cm = std::round((band.height_min_cm + u * (band.height_max_cm - band.height_min_cm)) * 10) / 10;
    const double bmi = band.bmi_min + v * (band.bmi_max - band.bmi_min);
    b.weight_kg = std::round(bmi * b.height_cm * b.height_cm / 1000) / 10;
    b.role = role;
    validate(b);
    out.push_back(b);
  }
  return out;
}

ClipSplit split_clip(int frames) {
  ClipSplit s;
  s.frames = std::max(0, frames);
  const int after_gap = s.frames - kWindowFrames;
  const int test = std::max(kWindowFrames, int(std::floor(kTestFraction * after_gap)));
  s.train_end = std::max(0, after_gap - test);
  s.test_begin = s.train_end + kWindowFrames;
  return s;
}

namespace {

std::vector<ClipSource> mocap_sources(const std::string& folder, std::vector<std::string>& activity) {
  const std::string csv = (std::filesystem::path(folder) / "clips.csv").string();
  const std::vector<ClipRow> rows = read_clips_csv(csv);
  std::vector<ClipSource> out;
  for (const ClipRow& r : rows) {
    if (r.activity.empty())
      throw Error::at(csv, r.line, "an activity (a column 'activity' with a label per clip)", "none");
    ClipSource c;
    c.path = r.file;
    c.motion.metres_per_unit = r.metres_per_unit;
    if (!r.up.empty()) c.motion.up = r.up == "z" ? UpAxis::z : UpAxis::y;
    c.meta.motion_id = std::filesystem::path(r.file).stem().string();
    c.meta.performer = "CMU" + r.subject;
    c.meta.category = r.category;
    c.meta.take = r.take;
    c.meta.source = r.file;
    out.push_back(c);
    activity.push_back(r.activity);
  }
  return out;
}

}  // namespace

BenchClips load_bench_clips(const BenchOptions& o) {
  std::vector<ClipSource> sources;
  std::vector<std::string> activity;
  if (o.mocap.empty()) {
    if (o.performers < 1) throw Error("har-bench: need at least 1 procedural performer");
    sources = embedded_clips(o.performers, 1, o.seconds, o.seed);
    for (const ClipSource& c : sources) activity.push_back(c.meta.category);
  } else {
    sources = mocap_sources(o.mocap, activity);
  }
  const std::string where = o.mocap.empty() ? "procedural clips" : o.mocap + "/clips.csv";
  std::set<std::string> known(activity.begin(), activity.end());
  for (const std::string& a : o.activities)
    if (!known.count(a))
      throw Error::in(where, "no clip of activity '" + a + "' (activities: " +
                                 join(std::vector<std::string>(known.begin(), known.end())) + ")");
  const std::set<std::string> named(o.activities.begin(), o.activities.end());

  BenchClips out;
  std::map<std::string, std::string> unusable;  // activity -> first reason
  std::set<std::string> usable;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    if (!named.empty() && !named.count(activity[i])) continue;
    Motion m = load_clip(sources[i], kFps);
    const ClipSplit split = split_clip(m.size());
    const std::string id = sources[i].meta.motion_id;
    if (!split.usable()) {
      const std::string why = id + " (" + activity[i] + ", " + std::to_string(m.size()) +
                              " frames): shorter than 3 windows of " + std::to_string(kWindowFrames) +
                              " frames (training part, gap, test part)";
      out.left_out.push_back(why);
      unusable.emplace(activity[i], why);
      continue;
    }
    usable.insert(activity[i]);
    out.clips.push_back({sources[i], activity[i], std::move(m), split});
  }
  for (const auto& [a, why] : unusable) {
    if (usable.count(a)) continue;
    if (named.count(a))
      throw Error::in(where, "activity '" + a + "' has no test window: " + why + "; leave the activity out");
    out.left_out.push_back("activity " + a + ": no clip long enough");
  }
  out.activities.assign(usable.begin(), usable.end());
  if (out.activities.size() < 2)
    throw Error::in(where, "need clips of at least 2 activities with a test window, found " +
                               std::to_string(out.activities.size()) +
                               (unusable.empty() ? std::string() : " (" + unusable.begin()->second + ")"));
  for (BenchClip& c : out.clips)
    c.label = int(std::lower_bound(out.activities.begin(), out.activities.end(), c.activity) -
                  out.activities.begin());
  for (const std::string& l : out.left_out) say(o, "har-bench: left out " + l);
  return out;
}

namespace {

// What identifies the benchmark's clips and split, recorded in the training
// set's config and checked against it.
nlohmann::json split_record(const BenchClips& clips) {
  nlohmann::json list = nlohmann::json::array();
  for (const BenchClip& c : clips.clips)
    list.push_back({{"motion_id", c.source.meta.motion_id},
                    {"frames", c.split.frames},
                    {"train_end", c.split.train_end}});
  return {{"window", kWindowFrames}, {"test_fraction", kTestFraction}, {"clips", list}};
}

}  // namespace

void write_bench_training_set(const std::string& path, const BenchOptions& o, int bodies, bool force) {
  check_dataset_output(path, force);
  const BenchClips clips = load_bench_clips(o);
  std::vector<ClipSource> parts;
  for (const BenchClip& c : clips.clips) {
    ClipSource s = c.source;
    s.end_frame = c.split.train_end;  // the training part only
    s.meta.take = 1;                  // every part is for training (ptnet train: take 1)
    parts.push_back(s);
  }
  SimulateDatasetOptions so;
  so.sim.placement = parse_placement(o.sensor.placement);
  so.seed = o.seed;
  so.threads = o.threads;
  so.force = force;
  so.noise_floor = false;
  so.generator = "ptnet har-bench training set";
  nlohmann::json cfg = {{"kind", "har-bench transfer training set: the clips' training parts only"},
                        {"mocap", o.mocap.empty() ? "procedural" : o.mocap},
                        {"band", "all"},
                        {"bodies", bodies},
                        {"placement", o.sensor.placement},
                        {"seed", o.seed},
                        {"har_bench_split", split_record(clips)}};
  so.config_json = cfg.dump();
  so.progress = o.progress;
  const std::vector<BodySpec> b = band_bodies(body_band("all"), bodies, o.seed, "all", "retargeted");
  say(o, "har-bench: training set of " + std::to_string(parts.size()) + " clips' training parts on " +
             std::to_string(b.size()) + " bodies of band all (" + path + ")");
  simulate_dataset(parts, b, path, so);
}

void check_bench_training_set(const std::string& path, const BenchOptions& o) {
  check_bench_training_set(path, load_bench_clips(o));
}

void check_bench_training_set(const std::string& path, const BenchClips& clips) {
  const Dataset d = Dataset::open(path);
  nlohmann::json cfg;
  try {
    cfg = nlohmann::json::parse(d.info().config_json);
  } catch (const nlohmann::json::exception&) {
    throw Error::in(path, "expected a har-bench training set, found a config that is not JSON");
  }
  if (!cfg.is_object() || !cfg.contains("har_bench_split"))
    throw Error::in(path, "expected a har-bench training set (its config records the split), found another dataset");
  const nlohmann::json& split = cfg["har_bench_split"];
  std::map<std::string, int> train_end;
  try {
    if (split.at("window").get<int>() != kWindowFrames)
      throw Error::in(path, "expected a split with windows of " + std::to_string(kWindowFrames) + " frames");
    for (const auto& c : split.at("clips")) train_end[c.at("motion_id").get<std::string>()] = c.at("train_end").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw Error::in(path, std::string("expected a har-bench split record, found a malformed one (") + e.what() + ")");
  }
  for (const SequenceMeta& s : d.sequences()) {
    const auto it = std::find_if(clips.clips.begin(), clips.clips.end(),
                                 [&](const BenchClip& c) { return c.source.meta.motion_id == s.motion_id; });
    if (it == clips.clips.end()) continue;  // a clip the benchmark does not test: no test part to leak
    if (s.frames > it->split.train_end || train_end[s.motion_id] > it->split.train_end)
      throw Error::in(path, "sequence " + s.name + " holds " + std::to_string(s.frames) +
                                " frames of " + s.motion_id + ", beyond its training part (" +
                                std::to_string(it->split.train_end) + " frames): test frames reached the model");
  }
}

}  // namespace ptnet::har
