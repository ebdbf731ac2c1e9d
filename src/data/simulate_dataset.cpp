// simulate_dataset(): every clip on every body, written as a dataset in
// chunks of jobs (see ptnet/simulate_dataset.hpp).
#include "ptnet/simulate_dataset.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <cstdio>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <nlohmann/json.hpp>

#include "core/parallel.hpp"
#include "core/zip_check.hpp"
#include "data/data_internal.hpp"
#include "ptnet/body.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace fs = std::filesystem;
namespace {

// The sequence of a motion on a body: "<motion_id>__<body_id>".
std::string sequence_name(const std::string& motion_id, const std::string& body_id) {
  return motion_id + "__" + body_id;
}

std::string default_config(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies,
                           const SimulateDatasetOptions& o) {
  const SimOptions& s = o.sim;
  nlohmann::ordered_json j;
  j["seed"] = o.seed;
  j["fps"] = o.fps;
  j["clips"] = clips.size();
  std::vector<double> speeds;  // recorded only when a clip is played at another speed
  for (const ClipSource& c : clips)
    if (std::find(speeds.begin(), speeds.end(), c.speed) == speeds.end()) speeds.push_back(c.speed);
  if (speeds.size() > 1 || (!speeds.empty() && speeds[0] != 1)) j["speeds"] = speeds;
  j["bodies"] = bodies.size();
  j["mat"] = {{"rows", s.mat.rows}, {"cols", s.mat.cols}, {"pitch_m", s.mat.pitch_m}};
  j["placement"] = placement_name(s.placement);
  if (s.placement == Placement::follow) j["follow_smoothing_s"] = s.follow_smoothing_s;
  j["compliance_m"] = s.compliance_m;
  j["subsamples"] = s.subsamples;
  j["com_filter_hz"] = s.com_filter_hz;
  j["noise_floor"] = o.noise_floor;
  j["sensor"] = {{"crosstalk", s.sensor.crosstalk},       {"saturation_kpa", s.sensor.saturation_kpa},
                 {"noise_sd_kpa", s.sensor.noise_sd_kpa}, {"threshold_kpa", s.sensor.threshold_kpa},
                 {"quantum_kpa", s.sensor.quantum_kpa}};
  return j.dump();
}

constexpr std::uint64_t kMaxSequences = 10000000;  // sequences of one dataset

// ---- the phases of run(), in order

// A clip's text that the dataset stores (its motion id names sequences and
// force files; the rest are attributes HDF5 declares UTF-8), checked before
// any work: the ids by name_problem, the attributes as UTF-8.
void check_clip_text(const ClipSource& c) {
  if (const std::string problem = name_problem(c.meta.motion_id); !problem.empty())
    throw Error::in(c.meta.source, "motion id " + escaped(c.meta.motion_id) + " " + problem +
                                       ": it names the clip's sequences (and force files)");
  for (const std::string* text : {&c.meta.performer, &c.meta.category, &c.meta.source})
    if (utf8_invalid_at(*text) != std::string::npos)
      throw Error::in(c.meta.source, escaped(*text, 80) + " is not UTF-8, which the dataset's attributes are: "
                                     "rename the file (or give the clips CSV as UTF-8)");
}

// Every sequence name once, known before any work: each clip's motion id
// and each body's id once (a clip a_x0.8.bvh beside a.bvh played at 0.8),
// each a name (name_problem), and no "<motion_id>__<body_id>" made twice
// by ids that hold "__".
void check_names(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies) {
  std::map<std::string, const ClipSource*> ids;
  bool split = false;  // an id holding "__": names may collide
  for (const ClipSource& c : clips) {
    check_clip_text(c);
    const auto [it, fresh] = ids.emplace(c.meta.motion_id, &c);
    if (!fresh)
      throw Error::in(c.meta.source, "motion id " + escaped(c.meta.motion_id) + " is also that of " +
                                         it->second->meta.source + ": every clip needs its own");
    split = split || c.meta.motion_id.find("__") != std::string::npos;
  }
  std::set<std::string> body_ids;
  for (const BodySpec& b : bodies) {
    if (!body_ids.insert(b.id).second) throw Error("simulate: body id " + escaped(b.id) + " given twice");
    if (const std::string problem = name_problem(b.id); !problem.empty())
      throw Error("simulate: body id " + escaped(b.id) + " " + problem + ": it names the body's sequences");
    split = split || b.id.find("__") != std::string::npos;
  }
  if (!split) return;
  std::set<std::string> names;
  for (const ClipSource& c : clips)
    for (const BodySpec& b : bodies)
      if (!names.insert(sequence_name(c.meta.motion_id, b.id)).second)
        throw Error::in(c.meta.source, "sequence name " + escaped(sequence_name(c.meta.motion_id, b.id)) +
                                           " made twice (motion and body ids holding \"__\")");
}

// Jobs [begin, end) of `jobs` in shard K of N (SimulateDatasetOptions::shard_index).
std::pair<int, int> shard_range(int jobs, int k, int n) {
  return {int(std::int64_t(jobs) * k / n), int(std::int64_t(jobs) * (k + 1) / n)};
}

// The force files of the jobs [begin, end): <motion_id>__<body_id>.<format>.
std::vector<std::string> force_files(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies,
                                     const SimulateDatasetOptions& o, int begin, int end) {
  std::vector<std::string> out;
  const int nb = int(bodies.size());
  for (int j = begin; j < end; ++j)
    out.push_back(sequence_name(clips[std::size_t(j / nb)].meta.motion_id, bodies[std::size_t(j % nb)].id) + "." +
                  table_format_name(o.forces_format));
  return out;
}

// The forces folder, before any work: not the dataset's own path, and each
// force file one check_output_path allows (never an input of the run).
void check_forces_dir(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies,
                      const std::string& out_path, const SimulateDatasetOptions& o) {
  if (o.forces_dir.empty()) return;
  std::error_code ec;
  if (fs::weakly_canonical(fs::absolute(o.forces_dir), ec) == fs::weakly_canonical(fs::absolute(out_path), ec))
    throw Error(field_text("forces_dir") + ": " + o.forces_dir + " is the dataset's own path (" + out_path +
                "): give the force files a folder of their own");
  const int jobs = int(clips.size() * bodies.size());
  const auto [begin, end] = o.shard_count > 1 && o.shard_index >= 0 && o.shard_index < o.shard_count
                                ? shard_range(jobs, o.shard_index, o.shard_count)
                                : std::pair<int, int>{0, jobs};
  check_outputs_in_folder(o.forces_dir, force_files(clips, bodies, o, begin, end), o.force);
}

// Threads to use; throws Error for impossible options, and for an output
// that may not be written, before any work.
int check_run(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies, const std::string& out_path,
              const SimulateDatasetOptions& options) {
  if (clips.empty()) throw Error("simulate: no clips to simulate");
  if (bodies.empty()) throw Error("simulate: no bodies to simulate on");
  check_range("fps", options.fps, kFpsRange);
  check_names(clips, bodies);
  check_dataset_output(out_path, options.force);  // before any work
  check_forces_dir(clips, bodies, out_path, options);
  if (options.threads < 0 || options.threads > max_threads())
    throw Error("simulate: threads must be in 0-" + std::to_string(max_threads()) + ", found " +
                std::to_string(options.threads));
  return options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

// 1. Every clip, loaded once: a bad file, or one that would not play at the
//    dataset's fps, fails the run before any simulation. Each clip's
//    placement on the mat is decided here, once, from the source motion;
//    every body's copy gets it scaled (MotionPlacement).
void load_clips(const std::vector<ClipSource>& clips, const SimulateDatasetOptions& options, int threads,
                std::vector<Motion>& motions, std::vector<MotionPlacement>& places) {
  const int nc = int(clips.size());
  motions.assign(clips.size(), Motion{});
  places.assign(clips.size(), MotionPlacement{});
  std::mutex progress_mutex;
  int loaded = 0;
  std::vector<std::vector<std::string>> warnings(clips.size());
  parallel_for(nc, threads, [&](int i) {
    const ClipSource& clip = clips[std::size_t(i)];
    motions[std::size_t(i)] = load_clip(clip, options.fps);
    if (!same_rate(motions[std::size_t(i)].fps, options.fps))
      throw Error::in(clip.path.empty() ? clip.meta.source : clip.path,
                      "plays at " + precise_text(motions[std::size_t(i)].fps) + " fps, not at the dataset's " +
                          precise_text(options.fps));
    places[std::size_t(i)] = place_motion(motions[std::size_t(i)], options.sim);
    warnings[std::size_t(i)] = dynamics_warnings(
        clips[std::size_t(i)].meta.motion_id,
        check_dynamics(motions[std::size_t(i)], options.sim, &places[std::size_t(i)]));
    if (options.progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      options.progress(progress_count("load", ++loaded, nc, "clips"));
    }
  });
  // In clip order, whatever the threads did first.
  for (const auto& lines : warnings)
    for (const std::string& w : lines)
      if (options.progress) options.progress(progress_line("simulate", "warning: " + w));
}

// SimulateDatasetOptions::chunk_jobs, 0 resolved: on one thread a few jobs
// (nothing to balance; the writer reads sequences still in the cache, and
// less memory is faulted in), on more 8 per thread to balance their load.
int jobs_per_chunk(const SimulateDatasetOptions& options, int threads) {
  if (options.chunk_jobs > 0) return options.chunk_jobs;
  return threads == 1 ? 4 : std::max(16, 8 * threads);
}

// Sizes before allocating: sequence count, then the memory of the metadata
// and of two chunks of simulated sequences (one written while the next is
// simulated), plus one per thread at work.
void check_sizes(const std::vector<Motion>& motions, std::size_t bodies, const std::string& out_path,
                 const SimulateDatasetOptions& options, int threads) {
  const int nc = int(motions.size());
  const std::uint64_t jobs = checked_mul(std::uint64_t(nc), bodies, out_path, "clips x bodies");
  if (jobs > std::uint64_t(kMaxSequences))
    throw Error::in(out_path, std::to_string(nc) + " clips x " + std::to_string(bodies) + " bodies = " +
                                  std::to_string(jobs) + " sequences, more than the " +
                                  std::to_string(kMaxSequences) + " a dataset may have");
  std::uint64_t longest = 0;
  for (const Motion& m : motions) longest = std::max<std::uint64_t>(longest, std::uint64_t(m.size()));
  const std::uint64_t chunk_jobs = std::min<std::uint64_t>(jobs, std::uint64_t(jobs_per_chunk(options, threads)));
  const std::uint64_t sequence_bytes = checked_mul(
      longest, checked_mul(std::uint64_t(options.sim.mat.rows) * std::uint64_t(options.sim.mat.cols), sizeof(float),
                           out_path, "mat cells"),
      out_path, "a sequence");
  check_memory(checked_mul(sequence_bytes, 2 * chunk_jobs + std::uint64_t(threads), out_path, "simulation") +
                   checked_mul(jobs, 512, out_path, "sequence list"),
               out_path, "simulating " + std::to_string(jobs) + " sequences of up to " + std::to_string(longest) +
                             " frames on a " + std::to_string(options.sim.mat.rows) + " x " +
                             std::to_string(options.sim.mat.cols) + " mat");
}

// The sequences' metadata [clips x bodies], clip-major; a clip without a
// category gets one guessed from its motion (into summary.categories).
std::vector<SequenceMeta> sequence_metas(const std::vector<ClipSource>& clips, const std::vector<Motion>& motions,
                                         const std::vector<BodySpec>& bodies, SimulateDatasetSummary& summary) {
  std::vector<SequenceMeta> metas;
  for (std::size_t c = 0; c < clips.size(); ++c) {
    SequenceMeta m = clips[c].meta;
    if (m.category.empty()) m.category = category_from_motion(motions[c]);
    summary.categories.push_back(m.category);
    for (const auto& b : bodies) {
      SequenceMeta s = m;
      s.body_id = b.id;
      s.name = sequence_name(m.motion_id, b.id);
      metas.push_back(std::move(s));
    }
  }
  return metas;
}

// Jobs j0..j1 (motion j / bodies, body j % bodies) retargeted onto their
// bodies' heights, with their motions' placements scaled alike.
void retarget_jobs(const std::vector<Motion>& motions, const std::vector<MotionPlacement>& places,
                   const std::vector<BodySpec>& bodies, int j0, int j1, int threads, std::vector<Motion>& retargeted,
                   std::vector<MotionPlacement>& placed) {
  const int nb = int(bodies.size());
  retargeted.assign(std::size_t(j1 - j0), Motion{});
  placed.assign(std::size_t(j1 - j0), MotionPlacement{});
  parallel_for(j1 - j0, threads, [&](int k) {
    const int j = j0 + k;
    const Motion& source = motions[std::size_t(j / nb)];
    const double height = bodies[std::size_t(j % nb)].height_cm;
    retargeted[std::size_t(k)] = retarget(source, height);
    placed[std::size_t(k)] = places[std::size_t(j / nb)].scaled(retarget_scale(source, height));
  });
}

// 2. Chunks of jobs: retarget, simulate, write (chunk i is written while
//    chunk i + 1 is simulated). Sequences on original bodies are read a
//    second time by the sensor model with another seed (the noise floor,
//    /floor/<name>; the pressure is simulated once); progress counts the
//    sequences.
void simulate_chunks(const std::vector<Motion>& motions, const std::vector<MotionPlacement>& places,
                     const std::vector<BodySpec>& bodies, const std::vector<Body>& built,
                     const std::vector<SequenceMeta>& metas, const SimulateDatasetOptions& options, int threads,
                     int begin, int end, DatasetWriter& writer, SimulateDatasetSummary& summary,
                     std::vector<ForceTable>& forces) {
  const int nb = int(bodies.size()), total = end - begin;
  const int chunk = jobs_per_chunk(options, threads);
  const auto with_floor = [&](int j) { return options.noise_floor && bodies[std::size_t(j % nb)].role == "original"; };
  int done = 0;
  std::future<void> writing;  // the previous chunk's writes
  // On an error the chunk being written finishes first (it references this frame).
  struct Wait {
    std::future<void>& f;
    ~Wait() {
      if (f.valid()) f.wait();
    }
  } wait_writer{writing};
  for (int j0 = begin; j0 < end; j0 += chunk) {
    const int j1 = std::min(end, j0 + chunk);
    std::vector<Motion> retargeted;
    std::vector<MotionPlacement> placed;
    retarget_jobs(motions, places, bodies, j0, j1, threads, retargeted, placed);
    // A floor is the sequence's pressure read again with another sensor seed.
    std::vector<SimJob> jobs;
    for (int j = j0; j < j1; ++j) {
      const std::string& name = metas[std::size_t(j)].name;
      jobs.push_back({&retargeted[std::size_t(j - j0)], &built[std::size_t(j % nb)],
                      sequence_seed(options.seed, name), &placed[std::size_t(j - j0)], {}});
      if (with_floor(j)) jobs.back().reread_seeds = {floor_seed(options.seed, name)};
    }
    auto floors = std::make_shared<std::vector<std::vector<PressureSequence>>>();
    std::vector<ForceTable> chunk_forces;
    auto seqs = std::make_shared<std::vector<PressureSequence>>(simulate_many(
        jobs, options.sim, threads,
        [&](const Progress& p) {
          if (options.progress)
            options.progress(
                progress_count("simulate", done + int(p.done) * (j1 - j0) / int(p.total), total, "sequences"));
        },
        floors.get(), options.forces_dir.empty() ? nullptr : &chunk_forces));
    for (ForceTable& f : chunk_forces) forces.push_back(std::move(f));
    if (writing.valid()) writing.get();  // the previous chunk is written (or its error thrown)
    // Written (compressed) on one thread while the next chunk is simulated, in
    // sequence order: the same bytes for any thread count.
    writing = std::async(std::launch::async, [&, seqs, floors, j0, j1] {
      for (int j = j0; j < j1; ++j) {
        const PressureSequence& s = (*seqs)[std::size_t(j - j0)];
        writer.add(metas[std::size_t(j)], s);
        for (const PressureSequence& f : (*floors)[std::size_t(j - j0)]) writer.add_floor(metas[std::size_t(j)].name, f);
        summary.frames += s.frames();
      }
    });
    done = j1 - begin;
  }
  if (writing.valid()) writing.get();
}

// What identifies the clips of a run on any host: per clip its metadata and
// how it is generated or read, with a BVH file's bytes (CRC-32), not its
// path (hosts may mount the files elsewhere) nor the loaded motion (floating
// point may differ between CPUs). CRC-32 of all that, in hex.
std::string clips_digest(const std::vector<ClipSource>& clips) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const ClipSource& c : clips) {
    nlohmann::ordered_json j = {{"motion_id", c.meta.motion_id}, {"performer", c.meta.performer},
                                {"category", c.meta.category},   {"take", c.meta.take}};
    if (c.path.empty()) {
      const GenerateOptions& g = c.procedural;
      j["procedural"] = {category_name(g.category), g.performer, g.take, g.seconds, g.height_cm, g.seed};
    } else {
      const MotionOptions& m = c.motion;
      j["bvh_crc32"] = crc32(read_file_bytes(c.path));
      j["read"] = {units_name(m.units), m.metres_per_unit, m.up == UpAxis::z ? "z" : "y", m.keep_tpose};
      if (!m.static_markers.empty()) j["static_crc32"] = crc32(read_file_bytes(m.static_markers));
      if (!m.marker_map.empty()) {  // a shipped map's name, or a map file's bytes
        const auto shipped = marker_map_names();
        j["marker_map"] = std::find(shipped.begin(), shipped.end(), m.marker_map) != shipped.end()
                              ? nlohmann::ordered_json(m.marker_map)
                              : nlohmann::ordered_json(crc32(read_file_bytes(m.marker_map)));
      }
    }
    all.push_back(std::move(j));
  }
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(crc32(all.dump())));
  return hex;
}

// --shard K/N: the jobs [J K / N, J (K + 1) / N) of J, and at the end of the
// config "shard": "K/N" and "run": what identifies the whole run beyond the
// options before them (its clips' digest, its J sequences), which ptnet
// merge checks and removes.
std::pair<int, int> shard_jobs(int jobs, const std::vector<ClipSource>& clips, const SimulateDatasetOptions& o,
                               const std::string& out_path, std::string& config_json) {
  const int k = o.shard_index, n = o.shard_count;
  if (n < 1 || k < 0 || k >= n)
    throw Error(field_text("shard") + ": expected K/N with 0 <= K < N, found " + std::to_string(k) +
                "/" + std::to_string(n));
  if (n == 1) return {0, jobs};
  if (n > jobs)
    throw Error::in(out_path, std::to_string(n) + " shards of " + std::to_string(jobs) +
                                  " sequences: at most one shard per sequence");
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(config_json);
  j["shard"] = std::to_string(k) + "/" + std::to_string(n);
  j["run"] = {{"clips", clips_digest(clips)}, {"sequences", jobs}};
  config_json = j.dump();
  return shard_range(jobs, k, n);
}

SimulateDatasetSummary run(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies,
                           const std::string& out_path, const SimulateDatasetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const int threads = check_run(clips, bodies, out_path, options);
  std::vector<Body> built;
  built.reserve(bodies.size());
  for (const auto& b : bodies) built.emplace_back(b);  // validates
  std::vector<Motion> motions;
  std::vector<MotionPlacement> places;
  load_clips(clips, options, threads, motions, places);
  check_sizes(motions, bodies.size(), out_path, options, threads);
  SimulateDatasetSummary summary;
  summary.clips = int(clips.size());
  summary.bodies = int(bodies.size());
  const std::vector<SequenceMeta> metas = sequence_metas(clips, motions, bodies, summary);
  DatasetInfo info;
  info.mat = options.sim.mat;
  info.fps = options.fps;
  info.generator = options.generator;
  info.compression = options.compression;
  info.config_json = options.config_json.empty() ? default_config(clips, bodies, options) : options.config_json;
  const auto [begin, end] = shard_jobs(int(metas.size()), clips, options, out_path, info.config_json);
  const std::vector<std::string> files =
      options.forces_dir.empty() ? std::vector<std::string>() : force_files(clips, bodies, options, begin, end);
  CommitGroup outputs;  // the dataset and its force files appear together, or none
  DatasetWriter writer(out_path, info, bodies, options.force);
  std::vector<ForceTable> forces;
  simulate_chunks(motions, places, bodies, built, metas, options, threads, begin, end, writer, summary, forces);
  writer.commit();
  if (!files.empty()) {
    make_folder(options.forces_dir);
    for (std::size_t k = 0; k < files.size(); ++k)
      write_force_table(forces[k], (fs::path(options.forces_dir) / files[k]).string(), options.force);
  }
  outputs.commit();
  summary.sequences = end - begin;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}
}  // namespace

SimulateDatasetSummary simulate_dataset(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies,
                                        const std::string& out_path, const SimulateDatasetOptions& options) {
  try {
    return run(clips, bodies, out_path, options);
  } catch (const Error& e) {
    // Errors are one line (HDF5's error stacks may hold line breaks).
    std::string text = e.message();
    for (char& ch : text)
      if (ch == '\n' || ch == '\r') ch = ' ';
    throw Error(text, e.kind());
  }
}

}  // namespace ptnet
