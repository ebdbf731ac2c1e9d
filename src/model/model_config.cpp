// ModelConfig validation, sizes, parameter/FLOP counts and the model
// directory's config.json. No Torch here.
#include "ptnet/model_config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <type_traits>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
using nlohmann::json;

Arch parse_arch(const std::string& text) {
  if (text == "faithful") return Arch::faithful;
  if (text == "skip") return Arch::skip;
  if (text == "residual") return Arch::residual;
  if (text == "frame") return Arch::frame;
  throw Error("--arch: expected faithful, skip, residual or frame, found \"" + text + "\"");
}

Align parse_align(const std::string& text) {
  if (text == "none") return Align::none;
  if (text == "zoom") return Align::zoom;
  throw Error("--align: expected none or zoom, found \"" + text + "\"");
}

const char* align_name(Align align) { return align == Align::zoom ? "zoom" : "none"; }

const char* arch_name(Arch arch) {
  switch (arch) {
    case Arch::skip: return "skip";
    case Arch::residual: return "residual";
    case Arch::frame: return "frame";
    default: return "faithful";
  }
}

void validate(const ModelConfig& c) {
  auto positive = [](const char* what, int v, int max) {
    if (v < 1 || v > max)
      throw Error(std::string("model: ") + what + " must be in 1-" + std::to_string(max) +
                  ", found " + std::to_string(v));
  };
  positive("window", c.window, 10000);
  positive("rows", c.rows, 100000);
  positive("cols", c.cols, 100000);
  for (int ch : c.channels) positive("channels", ch, 4096);
  positive("hidden", c.hidden, 1 << 16);
  positive("latent", c.latent, 1 << 16);
  if (c.context < 0 || c.context > 16)
    throw Error("model: context must be in 0-16, found " + std::to_string(c.context));
  if (c.contact && c.arch != Arch::frame)
    throw Error(std::string("model: a contact head needs the frame architecture, found ") + arch_name(c.arch));
}

std::array<int, 2> pooled_size(const ModelConfig& c, int level) {
  std::array<int, 2> s{c.rows, c.cols};
  for (int k = 0; k < level; ++k) s = {(s[0] + 1) / 2, (s[1] + 1) / 2};
  return s;
}

namespace {
// Arch::frame (model.hpp): six conv blocks (3x3, no bias; BatchNorm without
// affine; FiLM gamma and beta per channel), laterals 1x1, head 3x3 -> 1, FiLM
// MLP 2A -> hidden -> 2 x (sum of block widths). Per frame: parameters, and
// multiply-adds with p0, p1, p2 cells at full, half and quarter resolution.
struct FrameCounts {
  std::int64_t parameters = 0;
  double macs_per_frame = 0;
};
FrameCounts frame_counts(const ModelConfig& c) {
  using I = std::int64_t;
  const I k = 1 + 2 * I(c.context), c1 = c.channels[0], c2 = c.channels[1], c3 = c.channels[2];
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2);
  const double p0 = double(s0[0]) * s0[1], p1 = double(s1[0]) * s1[1], p2 = double(s2[0]) * s2[1];
  const I blocks[6][2] = {{k, c1}, {c1, c2}, {c2, c3}, {c3, c3}, {c2, c2}, {c1, c1}};
  const double at[6] = {p0, p1, p2, p2, p1, p0};
  FrameCounts f;
  I film = 0;
  for (int i = 0; i < 6; ++i) {
    f.parameters += blocks[i][0] * blocks[i][1] * 9;
    f.macs_per_frame += at[i] * 9.0 * double(blocks[i][0] * blocks[i][1]);
    film += 2 * blocks[i][1];
  }
  const I outputs = c.contact ? 2 : 1;                                      // pressure (+ contact logit)
  f.parameters += c3 * c2 + c2 + c2 * c1 + c1 + outputs * (c1 * 9 + 1);     // laterals, head
  f.macs_per_frame += p1 * double(c3 * c2) + p0 * double(c2 * c1) + p0 * 9.0 * double(c1 * outputs);
  const I conditions = 2 * kAttributes;
  f.parameters += conditions * I(c.hidden) + c.hidden + I(c.hidden) * film + film;  // FiLM MLP
  f.macs_per_frame += double(conditions) * c.hidden + double(c.hidden) * double(film);
  return f;
}
}  // namespace

std::int64_t parameter_count(const ModelConfig& c) {
  using I = std::int64_t;
  if (c.arch == Arch::frame) return frame_counts(c).parameters;
  const I t = c.window, c1 = c.channels[0], c2 = c.channels[1], c3 = c.channels[2];
  const I k = 9, skip = has_skips(c.arch) ? 2 : 1, a = kAttributes;
  auto s3 = pooled_size(c, 3);
  const I flat = c3 * s3[0] * s3[1];
  I n = 0;
  n += t * c1 * k + c1 + 2 * c1;                  // conv1 + bn1
  n += c1 * c2 * k + c2 + 2 * c2;                 // conv2 + bn2
  n += c2 * c3 * k + c3 + 2 * c3;                 // conv3 + bn3
  n += flat * c.hidden + c.hidden;                // fc_features
  n += (I(c.hidden) + a) * c.latent + c.latent;   // fc_latent
  n += (I(c.latent) + a) * flat + flat;           // fc_decode
  n += skip * c3 * c2 * k + c2 + 2 * c2;          // deconv3 + dbn3
  n += skip * c2 * c1 * k + c1 + 2 * c1;          // deconv2 + dbn2
  n += skip * c1 * t * k + t;                     // deconv1
  return n;
}

std::uint64_t model_memory_bytes(const ModelConfig& c, int batch, bool training) {
  // Every factor is bounded by validate(): the products fit in 64 bits.
  const double params = double(parameter_count(c)) * 4 * (training ? 4 : 1);
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2);
  const double per_window = 4.0 * (3.0 * c.window * s0[0] * s0[1] + 4.0 * c.channels[0] * s0[0] * s0[1] +
                                   4.0 * c.channels[1] * s1[0] * s1[1] + 4.0 * c.channels[2] * s2[0] * s2[1]);
  const double total = params + per_window * std::max(1, batch) * (training ? 2 : 1);
  return total > 1.8e19 ? std::uint64_t(1.8e19) : std::uint64_t(total);
}

double forward_flops(const ModelConfig& c) {
  if (c.arch == Arch::frame) return 2 * frame_counts(c).macs_per_frame * c.window;
  const double t = c.window, c1 = c.channels[0], c2 = c.channels[1], c3 = c.channels[2];
  const double k = 9, skip = has_skips(c.arch) ? 2 : 1, a = kAttributes;
  auto s0 = pooled_size(c, 0), s1 = pooled_size(c, 1), s2 = pooled_size(c, 2), s3 = pooled_size(c, 3);
  const double p0 = double(s0[0]) * s0[1], p1 = double(s1[0]) * s1[1], p2 = double(s2[0]) * s2[1];
  const double flat = c3 * s3[0] * s3[1];
  double macs = t * c1 * k * p0 + c1 * c2 * k * p1 + c2 * c3 * k * p2;                  // encoder
  macs += flat * c.hidden + (c.hidden + a) * c.latent + (c.latent + a) * flat;           // FCs
  macs += skip * (c3 * c2 * k * p2 + c2 * c1 * k * p1 + c1 * t * k * p0);               // decoder
  return 2 * macs;
}

std::array<float, 3> Normalisation::attributes(const BodySpec& body) const {
  return {body.sex == Sex::male ? 1.0f : 0.0f,
          float((body.height_cm - height_mean_cm) / height_std_cm),
          float((body.weight_kg - weight_mean_kg) / weight_std_kg)};
}

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
    throw Error::in(where, e.what());
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
  if (!fs::exists(dir, ec)) throw Error::in(dir, "no such model folder");
  if (!fs::is_directory(dir, ec)) throw Error::in(dir, "is not a folder (expected a model folder with config.json)");
  const std::string path = (fs::path(dir) / "config.json").string();
  if (!fs::exists(path, ec)) throw Error::in(path, "no such file (is " + dir + " a ptnet model folder?)");
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

std::string recorded_digest(const ModelDir& dir, const std::string& file, int* epoch) {
  if (epoch) *epoch = -1;
  if (!dir.integrity.is_object() || !dir.integrity.contains(file)) return "";
  const json& v = dir.integrity.at(file);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_object() && v.contains("digest") && v["digest"].is_string()) {
    if (epoch && v.contains("epoch") && v["epoch"].is_number_integer()) *epoch = v["epoch"].get<int>();
    return v["digest"].get<std::string>();
  }
  return "";
}

void record_digest(ModelDir& dir, const std::string& file, const std::string& digest, int epoch) {
  if (!dir.integrity.is_object()) dir.integrity = json::object();
  dir.integrity[file] = epoch >= 0 ? json{{"epoch", epoch}, {"digest", digest}} : json(digest);
}

}  // namespace ptnet
