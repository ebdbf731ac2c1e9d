// The list of clips to simulate: a clips CSV, BVH files and folders, or the
// embedded procedural motions; loading one clip.
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/csv.hpp"
#include "data/data_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/simulate_dataset.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace fs = std::filesystem;

namespace {

// A motion file a folder is searched for: BVH or markers (.trc, .c3d).
bool is_motion_file(const fs::path& p) {
  const std::string ext = lower(p.extension().string());
  return ext == ".bvh" || ext == ".trc" || ext == ".c3d";
}

// A path key for matching --motions files against clips.csv rows.
std::string key_of(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return p.lexically_normal().string();
}

}  // namespace

std::vector<ClipRow> read_clips_csv(const std::string& path) {
  note_input(path);
  return parse_clips_csv(read_text_file(path), path);
}

std::vector<ClipRow> parse_clips_csv(const std::string& text, const std::string& path) {
  const CsvTable t = parse_csv(text, path);
  const fs::path folder = fs::path(path).parent_path();
  const std::string columns = "file,subject,category,take[,metres_per_unit,up,marker_map,static]";
  const int c_file = t.required("file", columns), c_subject = t.required("subject", columns),
            c_category = t.required("category", columns), c_take = t.required("take", columns),
            c_mpu = t.column("metres_per_unit"), c_up = t.column("up"),
            c_activity = t.column("activity"), c_map = t.column("marker_map"), c_static = t.column("static");
  std::vector<ClipRow> rows;
  for (const CsvRow& row : t.rows) {
    const long number = row.line;
    auto get = [&](int c) -> const std::string& { return CsvTable::field(row, c); };
    ClipRow r;
    r.line = number;
    const std::string& file = get(c_file);
    if (file.empty()) throw Error::at(path, number, "a file name", "an empty field");
    r.subject = get(c_subject);
    if (r.subject.empty()) throw Error::at(path, number, "a subject", "an empty field");
    try {
      r.category = category_name(parse_category(lower(get(c_category))));
    } catch (const Error&) {
      throw Error::at(path, number, "category walking, rom, freestyle or acting", escaped(get(c_category)));
    }
    const std::string& take = get(c_take);
    std::size_t used = 0;
    long t_value = 0;
    try {
      t_value = std::stol(take, &used);
    } catch (...) {
      used = 0;
    }
    if (used != take.size() || take.empty() || t_value < 1 || t_value > 1000000)
      throw Error::at(path, number, "take as an integer in 1-1000000", escaped(take));
    r.take = int(t_value);
    const std::string& mpu = get(c_mpu);
    if (!mpu.empty()) {
      char* end = nullptr;
      r.metres_per_unit = std::strtod(mpu.c_str(), &end);
      if (end != mpu.c_str() + mpu.size() || !(r.metres_per_unit > 0) || !std::isfinite(r.metres_per_unit))
        throw Error::at(path, number, "metres_per_unit as a positive number", escaped(mpu));
    }
    r.activity = lower(get(c_activity));
    r.up = lower(get(c_up));
    if (!r.up.empty() && r.up != "y" && r.up != "z") throw Error::at(path, number, "up y or z", escaped(get(c_up)));
    // Checked before the work (a FIFO would block the run, a device never
    // end) and noted: no output of the run may replace them.
    r.file = listed_input(path, number, "clip file", folder.string(), file);
    r.static_markers = listed_input(path, number, "static", folder.string(), get(c_static));
    r.marker_map = marker_map_in(path, number, folder.string(), get(c_map));
    rows.push_back(r);
  }
  if (rows.empty()) throw Error::in(path, "no clips listed after the header");
  return rows;
}

std::string category_from_name(const std::string& path) {
  const std::string s = lower(fs::path(path).stem().string());
  auto has = [&](const char* w) { return s.find(w) != std::string::npos; };
  if (has("walk")) return "walking";
  if (has("rom") || has("range") || has("exercise")) return "rom";
  if (has("dance") || has("freestyle")) return "freestyle";
  if (has("acting") || has("act_") || has("_act")) return "acting";
  return "";
}

std::string category_from_motion(const Motion& motion) {
  const int T = motion.size();
  if (T < 2 || !(motion.fps > 0)) return "freestyle";
  double path = 0;
  for (int t = 1; t < T; ++t)
    path += (motion.frames[t][kPelvis] - motion.frames[t - 1][kPelvis]).head<2>().norm();
  const double speed = path / ((T - 1) / motion.fps);
  return speed >= 0.4 && speed <= 2.5 && path >= 1.5 ? "walking" : "freestyle";
}

std::vector<ClipSource> clips_from_files(const std::vector<std::string>& inputs, const std::string& clips_csv,
                                         const MotionOptions& defaults) {
  // Expand the inputs into BVH files.
  std::vector<std::string> files;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      for (auto it = fs::recursive_directory_iterator(in, ec); !ec && it != fs::recursive_directory_iterator();
           it.increment(ec))
        // Not only regular files: a FIFO or device named x.bvh is refused when read, not skipped.
        if (!it->is_directory(ec) && is_motion_file(it->path())) found.push_back(it->path().string());
      if (ec) throw Error::in(in, "cannot list folder: " + ec.message(), ErrorKind::io);
      if (found.empty()) throw Error::in(in, "folder holds no .bvh, .trc or .c3d files");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::exists(in, ec)) {
      files.push_back(in);
    } else {
      throw Error::in(in, "no such file", ErrorKind::not_found);
    }
  }

  std::vector<ClipSource> clips;
  auto make = [&](const std::string& file) {
    ClipSource c;
    c.path = file;
    c.motion = defaults;
    c.meta.source = file;
    c.meta.motion_id = fs::path(file).stem().string();
    return c;
  };
  if (!clips_csv.empty()) {
    const std::vector<ClipRow> rows = read_clips_csv(clips_csv);
    std::map<std::string, const ClipRow*> by_key;
    for (const auto& r : rows) by_key.emplace(key_of(r.file), &r);
    auto from_row = [&](const std::string& file, const ClipRow& r) {
      ClipSource c = make(file);
      c.meta.performer = r.subject;
      c.meta.category = r.category;
      c.meta.take = r.take;
      if (r.metres_per_unit > 0) c.motion.metres_per_unit = r.metres_per_unit;
      if (!r.up.empty()) c.motion.up = parse_up_axis(r.up);
      if (!r.marker_map.empty()) c.motion.marker_map = r.marker_map;
      if (!r.static_markers.empty()) c.motion.static_markers = r.static_markers;
      return c;
    };
    if (inputs.empty()) {
      for (const auto& r : rows) clips.push_back(from_row(r.file, r));
    } else {
      for (const auto& f : files) {
        auto it = by_key.find(key_of(f));
        if (it == by_key.end()) throw Error::in(f, "not listed in " + clips_csv);
        clips.push_back(from_row(f, *it->second));
      }
    }
  } else {
    if (files.empty()) throw Error("simulate: no motions given");
    for (const auto& f : files) {
      ClipSource c = make(f);
      const std::string stem = fs::path(f).stem().string();
      const std::size_t us = stem.find('_');
      c.meta.performer = us != std::string::npos && us > 0 ? stem.substr(0, us) : stem;
      c.meta.category = category_from_name(f);  // "" : guessed from the motion when loaded
      c.meta.take = 1;
      clips.push_back(c);
    }
  }
  std::map<std::string, std::string> seen;
  for (const auto& c : clips) {
    auto [it, fresh] = seen.emplace(c.meta.motion_id, c.meta.source);
    if (!fresh)
      throw Error::in(c.meta.source, "motion id '" + c.meta.motion_id + "' also used by " + it->second +
                                         " (file stems must be unique)");
  }
  return clips;
}

std::vector<ClipSource> embedded_clips(int performers, int takes, double seconds, std::uint64_t seed,
                                       double fps) {
  const EmbeddedCorpusRanges& r = kEmbeddedCorpusRanges;
  check_range("performers", performers, r.performers);
  check_range("takes", takes, r.takes);
  check_range("seconds", seconds, r.seconds);
  std::vector<ClipSource> clips;
  for (int p = 1; p <= performers; ++p)
    for (Category cat : kCategories)
      for (int take = 1; take <= takes; ++take) {
        ClipSource c;
        c.procedural.category = cat;
        c.procedural.performer = p;
        c.procedural.take = take;
        c.procedural.seconds = seconds;
        c.procedural.fps = fps;
        c.procedural.seed = seed;
        c.meta.motion_id = motion_id(p, cat, take);
        c.meta.performer = "P" + std::to_string(p);
        c.meta.category = category_name(cat);
        c.meta.take = take;
        c.meta.source = "procedural:" + c.meta.motion_id;
        clips.push_back(std::move(c));
      }
  return clips;
}

std::vector<ClipSource> clips_at_speeds(const std::vector<ClipSource>& clips, const std::vector<double>& speeds) {
  if (speeds.empty()) throw Error(field_text("speeds") + ": expected at least one speed");
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    check_range("speeds", speeds[i], kClipSpeedRange);
    // A speed is what its label says: 1.000001 would be "_x1", 0.8000001 "_x0.8" beside 0.8.
    if (std::strtod(number_text(speeds[i]).c_str(), nullptr) != speeds[i])
      throw Error(field_text("speeds") + ": " + precise_text(speeds[i]) + " has more digits than its label _x" +
                  number_text(speeds[i]) + " shows (at most 6 significant digits)");
    for (std::size_t j = 0; j < i; ++j)
      if (speeds[j] == speeds[i]) throw Error(field_text("speeds") + ": " + number_text(speeds[i]) + " given twice");
  }
  std::vector<ClipSource> out;
  out.reserve(clips.size() * speeds.size());
  for (const ClipSource& c : clips)
    for (double s : speeds) {
      ClipSource v = c;
      v.speed = c.speed * s;
      if (s != 1) {
        v.meta.motion_id += "_x" + number_text(s);
        v.meta.source += " x" + number_text(s);
      }
      out.push_back(std::move(v));
    }
  return out;
}

namespace {

// Frames [first_frame, end_frame) of a loaded clip (ClipSource); the span
// counts frames of the clip at its own speed, so a clip played at speed s
// (loaded at fps / s) keeps the frames of [first / s, end / s).
Motion clip_span(Motion m, const ClipSource& clip) {
  if (clip.first_frame == 0 && clip.end_frame == 0) return m;
  const std::string& where = clip.path.empty() ? clip.meta.motion_id : clip.path;
  const auto at_speed = [&](int frame) { return int(std::lround(frame / clip.speed)); };
  const int first = at_speed(clip.first_frame);
  const int want_end = clip.end_frame > 0 ? at_speed(clip.end_frame) : m.size();
  const int end = std::min(want_end, m.size());  // at speed != 1 rounding may pass the last frame by one
  if (first < 0 || want_end > m.size() + (clip.speed != 1 ? 1 : 0) || first >= end)
    throw Error::in(where, "expected a frame span within 0-" + std::to_string(m.size()) + ", found " +
                               std::to_string(first) + "-" + std::to_string(want_end));
  m.frames = std::vector<Pose>(m.frames.begin() + first, m.frames.begin() + end);
  m.start_s += first * clip.speed / m.fps;  // the span's first frame on the recording's clock
  return m;
}

}  // namespace

// A clip at speed s is read at fps / s and played at fps.
Motion load_clip(const ClipSource& clip, double fps) {
  check_range("speed", clip.speed, kClipSpeedRange);
  const double read_fps = fps / clip.speed;
  Motion m;
  if (clip.path.empty()) {
    GenerateOptions g = clip.procedural;
    g.fps = read_fps;
    m = generate_motion(g);
    m.name = clip.meta.motion_id;
  } else {
    MotionOptions o = clip.motion;
    o.fps = read_fps;
    m = load_motion(clip.path, o);
    if (m.size() == 0) throw Error::in(clip.path, "no frames");
  }
  m.fps *= clip.speed;  // the frames read at fps / speed play at fps
  return clip_span(std::move(m), clip);
}

}  // namespace ptnet
