// Real recordings into the dataset format (ptnet/har.hpp, import_recordings).
#include <algorithm>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/csv.hpp"
#include "har/har_internal.hpp"
#include "ptnet/body_spec.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/io.hpp"
#include "ptnet/npy.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::har {
namespace {

// [T, rows, cols] kPa from a CSV of one frame per line. The text and the
// frames are held once each (the frames counted and checked against the
// available memory before they are parsed).
PressureSequence read_csv_frames(const std::string& path, const MatSpec& mat, double fps) {
  const std::string text = read_text_file(path);
  const auto lines = [&](auto&& visit) {
    long line = 0;
    for (std::size_t at = 0; at < text.size();) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      ++line;
      const std::string_view row(text.data() + at, end - at);
      if (!trim(row).empty()) visit(row, line);
      at = end + 1;
    }
  };
  std::uint64_t frames = 0;
  lines([&](std::string_view, long) { ++frames; });
  if (frames == 0) throw Error::in(path, "no frames");
  const std::uint64_t values = checked_mul(frames, std::uint64_t(mat.cells()), path, "the frames' values");
  check_memory(checked_mul(values, sizeof(float), path, "the frames' bytes"), path, "the frames");
  PressureSequence s(mat, int(frames), fps);  // frames < lines of a text under 1 GiB
  std::size_t i = 0;
  lines([&](std::string_view row, long line) {
    const auto fields = split(row, ',');
    if (int(fields.size()) != mat.cells())
      throw Error::at(path, line, std::to_string(mat.cells()) + " values (" + std::to_string(mat.rows) + " x " +
                                      std::to_string(mat.cols) + ")",
                      std::to_string(fields.size()));
    for (const auto& f : fields) {
      double v = 0;
      if (!parse_number(f, v)) throw Error::at(path, line, "a number", escaped(f));
      s.kpa[i++] = float(v);
    }
  });
  check_pressure(s.kpa.data(), s.kpa.size(), mat.cells(), path, "");
  return s;
}

}  // namespace

void import_recordings(const std::string& manifest, const std::string& out,
                       const ImportOptions& options, bool force) {
  namespace fs = std::filesystem;
  check_dataset_output(out, force);
  const CsvTable t = read_csv(manifest);
  const std::string columns = "subject,sex,height_cm,weight_kg,file[,category]";
  const int c_subject = t.required("subject", columns), c_sex = t.required("sex", columns),
            c_height = t.required("height_cm", columns), c_weight = t.required("weight_kg", columns),
            c_file = t.required("file", columns), c_category = t.column("category");
  struct Row {
    std::string subject, file, category;
    long line;
  };
  std::vector<Row> rows;
  std::vector<BodySpec> bodies;
  std::map<std::string, std::size_t> body_of;
  for (const CsvRow& row : t.rows) {
    const long line = row.line;
    auto f = [&](int c) -> const std::string& { return CsvTable::field(row, c); };
    if (f(c_subject).empty()) throw Error::at(manifest, line, "a subject id", "an empty field");
    BodySpec b = parse_body_fields(manifest, line, f(c_subject), f(c_sex), f(c_height), f(c_weight));
    b.role = "original";
    auto it = body_of.find(b.id);
    if (it == body_of.end()) {
      body_of[b.id] = bodies.size();
      bodies.push_back(b);
    } else {
      const BodySpec& a = bodies[it->second];
      if (a.sex != b.sex || a.height_cm != b.height_cm || a.weight_kg != b.weight_kg)
        throw Error::at(manifest, line, "the attributes given before for subject " + b.id,
                        "different ones");
    }
    rows.push_back({b.id, f(c_file), f(c_category), line});
  }
  if (rows.empty()) throw Error::in(manifest, "no recordings listed");

  DatasetInfo info;
  info.mat = options.mat;
  info.fps = options.fps;
  info.generator = std::string("ptnet ") + PTNET_VERSION + " import";
  info.config_json = nlohmann::json{{"manifest", fs::path(manifest).filename().string()}}.dump();
  DatasetWriter w(out, info, bodies, force);
  const fs::path base = fs::path(manifest).parent_path();
  std::map<std::string, int> names;
  for (const Row& r : rows) {
    const fs::path file = fs::path(r.file).is_absolute() ? fs::path(r.file) : base / r.file;
    const std::string ext = file.extension().string();
    if (ext != ".npy" && ext != ".csv") throw Error::at(manifest, r.line, "a .npy or .csv file", escaped(r.file));
    PressureSequence seq;
    if (ext == ".npy") seq = read_npy_sequence(file.string(), options.mat, options.fps);
    else if (ext == ".csv") seq = read_csv_frames(file.string(), options.mat, options.fps);
    else throw Error::at(manifest, r.line, "a .npy or .csv file", escaped(r.file));
    SequenceMeta m;
    m.motion_id = file.stem().string();
    m.body_id = r.subject;
    m.name = m.motion_id + "__" + r.subject;
    if (names[m.name]++) throw Error::at(manifest, r.line, "a new recording", escaped(m.name) + " again");
    m.performer = r.subject;
    m.category = r.category;
    m.take = 1;
    m.source = file.string();
    w.add(m, seq);
  }
  w.commit();
}

void write_finetune_set(const std::string& real_path, const std::vector<std::string>& subjects,
                        const std::string& out, bool force) {
  check_dataset_output(out, force);
  const Dataset real = Dataset::open(real_path);
  if (subjects.empty()) throw Error::in(real_path, "no fine-tuning subjects given");
  std::vector<std::string> ids;
  for (const auto& token : subjects) {
    const std::string id = resolve_subject(real, token);
    if (std::find(ids.begin(), ids.end(), id) != ids.end())
      throw Error::in(real_path, "subject " + id + " listed twice");
    ids.push_back(id);
  }
  std::vector<BodySpec> bodies;
  for (const auto& id : ids) {
    BodySpec b = real.body(id);
    b.role = "retargeted";  // what the training protocol trains on
    bodies.push_back(b);
  }
  DatasetInfo info = real.info();
  info.generator = std::string("ptnet ") + PTNET_VERSION + " import (fine-tuning set)";
  nlohmann::json cfg = {{"fine_tuning_set_of", real_path}, {"subjects", ids}};
  try {
    cfg["source_config"] = nlohmann::json::parse(real.info().config_json);
  } catch (const std::exception&) {
    cfg["source_config"] = real.info().config_json;
  }
  info.config_json = cfg.dump();
  DatasetWriter w(out, info, bodies, force);
  int written = 0;
  for (const SequenceMeta& meta : real.sequences()) {
    if (std::find(ids.begin(), ids.end(), meta.body_id) == ids.end()) continue;
    SequenceMeta m = meta;
    m.take = 1;
    w.add(m, real.read(meta.name));
    ++written;
  }
  if (written == 0) throw Error::in(real_path, "the fine-tuning subjects have no sequences");
  w.commit();
}

}  // namespace ptnet::har
