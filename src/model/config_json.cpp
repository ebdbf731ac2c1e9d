// config.json of a model folder: ModelConfig and ModelDir to and from JSON,
// every field type-checked and validated on the way in
// (ptnet/model_config.hpp). The weights' digests it records: integrity.cpp.
// No Torch here.
#include <cmath>
#include <filesystem>
#include <type_traits>

#include "model/model_config_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/model_config.hpp"

namespace ptnet {
using nlohmann::json;

json to_json(const ModelConfig& c) {
  return json{{"arch", arch_name(c.arch)}, {"align", align_name(c.align)}, {"window", c.window}, {"rows", c.rows},
              {"cols", c.cols}, {"channels", c.channels}, {"hidden", c.hidden},
              {"latent", c.latent}, {"context", c.context}, {"contact", c.contact}, {"mirror", c.mirror},
              {"attributes", kAttributes},
              {"output", "relu"}, {"pooling", "max 2x2 ceil, indices shared with the decoder"},
              {"parameters", parameter_count(c)}};
}

namespace {

const json& field(const json& j, const char* key, const std::string& where) {
  if (!j.is_object() || !j.contains(key))
    throw Error::in(where, std::string("missing field \"") + key + "\"");
  return j.at(key);
}

[[noreturn]] void wrong(const char* key, const json& v, const char* expected, const std::string& where) {
  throw Error::in(where, std::string("field \"") + key + "\": expected " + expected + ", found " +
                             escaped(v.dump(), 40));
}

template <typename T>
T get(const json& j, const char* key, const std::string& where) {
  const json& v = field(j, key, where);
  if constexpr (std::is_same_v<T, int>) {
    // Integers only, in int range: 1e10 or 2.5 are not silently truncated.
    if (v.is_number_unsigned()) {
      if (v.get<std::uint64_t>() <= 0x7fffffffu) return int(v.get<std::uint64_t>());
    } else if (v.is_number_integer()) {
      const std::int64_t i = v.get<std::int64_t>();
      if (i >= -0x7fffffffLL && i <= 0x7fffffffLL) return int(i);
    }
    wrong(key, v, "an integer", where);
  } else if constexpr (std::is_same_v<T, bool>) {
    if (!v.is_boolean()) wrong(key, v, "true or false", where);
    return v.get<bool>();
  } else if constexpr (std::is_same_v<T, double>) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) wrong(key, v, "a finite number", where);
    return v.get<double>();
  } else if constexpr (std::is_same_v<T, std::array<int, 3>>) {
    if (!v.is_array() || v.size() != 3) wrong(key, v, "three integers", where);
    std::array<int, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) out[i] = get<int>(json{{key, v[i]}}, key, where);
    return out;
  } else {
    try {
      return v.get<T>();
    } catch (const json::exception&) {
      wrong(key, v, "a string", where);
    }
  }
}

}  // namespace

ModelConfig model_config_from_json(const json& j, const std::string& where) {
  ModelConfig c;
  const std::string arch = get<std::string>(j, "arch", where);
  try {
    c.arch = parse_arch(arch);
  } catch (const Error&) {
    throw Error::in(where, "unknown architecture " + escaped(arch));
  }
  if (j.contains("align")) {
    const std::string align = get<std::string>(j, "align", where);
    if (align == "zoom") c.align = Align::zoom;
    else if (align != "none") throw Error::in(where, "unknown input alignment " + escaped(align));
  }
  c.window = get<int>(j, "window", where);
  c.rows = get<int>(j, "rows", where);
  c.cols = get<int>(j, "cols", where);
  c.channels = get<std::array<int, 3>>(j, "channels", where);
  c.hidden = get<int>(j, "hidden", where);
  c.latent = get<int>(j, "latent", where);
  if (j.contains("context")) c.context = get<int>(j, "context", where);
  if (j.contains("contact")) c.contact = get<bool>(j, "contact", where);
  if (j.contains("mirror")) c.mirror = get<bool>(j, "mirror", where);
  try {
    validate(c);
  } catch (const Error& e) {
    throw Error::in(where, e.message(), e.kind());
  }
  return c;
}

json to_json(const ModelDir& d) {
  return json{{"format", kModelFormat},
              {"version", kModelVersion},
              {"architecture", to_json(d.model)},
              {"window", d.model.window},
              {"mat", {{"rows", d.mat.rows}, {"cols", d.mat.cols}, {"pitch_m", d.mat.pitch_m}}},
              {"fps", d.fps},
              {"normalisation",
               {{"pressure_scale_kpa", d.norm.pressure_scale_kpa},
                {"height_mean_cm", d.norm.height_mean_cm},
                {"height_std_cm", d.norm.height_std_cm},
                {"weight_mean_kg", d.norm.weight_mean_kg},
                {"weight_std_kg", d.norm.weight_std_kg},
                {"contact_threshold_kpa", d.norm.contact_threshold_kpa},
                {"min_reading_kpa", d.norm.min_reading_kpa},
                {"sex", "female 0, male 1"}}},
              {"data", d.data.is_null() ? json::object() : d.data},
              {"options", d.options.is_null() ? json::object() : d.options},
              {"metrics", d.metrics.is_null() ? json::object() : d.metrics},
              {"integrity", d.integrity.is_null() ? json::object() : d.integrity}};
}

ModelDir read_model_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(dir, ec)) throw Error::in(dir, "no such model folder", ErrorKind::not_found);
  if (!fs::is_directory(dir, ec)) throw Error::in(dir, std::string("is not a folder (expected a model folder with ") + ModelFiles::kConfig + ")");
  const std::string path = ModelFiles(dir).config();
  if (!fs::exists(path, ec))
    throw Error::in(path, "no such file (is " + dir + " a ptnet model folder?)",
                    ErrorKind::not_found);
  return parse_model_config(read_text_file(path, kMaxConfigBytes), path, dir);
}

ModelDir parse_model_config(const std::string& text, const std::string& path, const std::string& dir) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // "[json.exception.out_of_range.406] number overflow parsing '1e400'" -> the part after "] "
    std::string why = e.what();
    const auto cut = why.find("] ");
    if (cut != std::string::npos) why = why.substr(cut + 2);
    if (why.size() > 120) why = why.substr(0, 120) + "...";
    throw Error::in(path, "not valid JSON (" + why + ")");
  }
  if (!j.is_object()) throw Error::in(path, "not a ptnet model config (expected a JSON object)");
  if (get<std::string>(j, "format", path) != kModelFormat)
    throw Error::in(path, std::string("expected format \"") + kModelFormat + "\", found " +
                              escaped(j.at("format").get<std::string>()));
  int version = get<int>(j, "version", path);
  if (version != kModelVersion)
    throw Error::in(path, "expected version " + std::to_string(kModelVersion) + ", found " +
                              std::to_string(version));
  ModelDir d;
  d.path = dir;
  d.model = model_config_from_json(field(j, "architecture", path), path);
  const json& mat = field(j, "mat", path);
  d.mat.rows = get<int>(mat, "rows", path);
  d.mat.cols = get<int>(mat, "cols", path);
  d.mat.pitch_m = get<double>(mat, "pitch_m", path);
  if (d.mat.rows != d.model.rows || d.mat.cols != d.model.cols)
    throw Error::in(path, "mat size and architecture disagree");
  if (j.contains("window") && get<int>(j, "window", path) != d.model.window)
    throw Error::in(path, "window " + std::to_string(get<int>(j, "window", path)) + " disagrees with the architecture's " +
                              std::to_string(d.model.window));
  if (!(d.mat.pitch_m > 0 && d.mat.pitch_m <= 10)) throw Error::in(path, "mat pitch_m must be in (0, 10] m");
  d.fps = get<double>(j, "fps", path);
  if (!(d.fps >= 1 && d.fps <= 1000)) throw Error::in(path, "fps " + number_text(d.fps) + " is not in [1, 1000]");
  const json& n = field(j, "normalisation", path);
  d.norm.pressure_scale_kpa = get<double>(n, "pressure_scale_kpa", path);
  d.norm.height_mean_cm = get<double>(n, "height_mean_cm", path);
  d.norm.height_std_cm = get<double>(n, "height_std_cm", path);
  d.norm.weight_mean_kg = get<double>(n, "weight_mean_kg", path);
  d.norm.weight_std_kg = get<double>(n, "weight_std_kg", path);
  if (n.contains("contact_threshold_kpa")) d.norm.contact_threshold_kpa = get<double>(n, "contact_threshold_kpa", path);
  if (!(d.norm.contact_threshold_kpa >= 0) || !std::isfinite(d.norm.contact_threshold_kpa))
    throw Error::in(path, "normalisation.contact_threshold_kpa must be >= 0");
  if (n.contains("min_reading_kpa")) d.norm.min_reading_kpa = get<double>(n, "min_reading_kpa", path);
  if (!(d.norm.min_reading_kpa >= 0)) throw Error::in(path, "normalisation.min_reading_kpa must be >= 0");
  for (double v : {d.norm.pressure_scale_kpa, d.norm.height_std_cm, d.norm.weight_std_kg})
    if (!(v > 0) || !std::isfinite(v)) throw Error::in(path, "normalisation scales must be > 0");
  if (j.contains("data")) d.data = j["data"];
  if (j.contains("options")) d.options = j["options"];
  if (j.contains("metrics")) d.metrics = j["metrics"];
  if (j.contains("integrity")) {
    d.integrity = j["integrity"];
    if (!d.integrity.is_object()) throw Error::in(path, "field \"integrity\" must be an object");
  }
  return d;
}

}  // namespace ptnet
