// ModelConfig: the architecture and alignment names, the validation of a
// configuration, pooled sizes and the attribute normalisation
// (ptnet/model_config.hpp). The cost model: cost_model.cpp; config.json:
// config_json.cpp. No Torch here.
#include "ptnet/model_config.hpp"

#include <cmath>
#include <filesystem>
#include <string>

#include "model/model_config_internal.hpp"
#include "ptnet/error.hpp"

namespace ptnet {

Arch parse_arch(const std::string& text) {
  if (text == "faithful") return Arch::faithful;
  if (text == "skip") return Arch::skip;
  if (text == "residual") return Arch::residual;
  if (text == "frame") return Arch::frame;
  throw Error(field_text("arch") + ": expected faithful, skip, residual or frame, found \"" + text +
              "\"");
}

Align parse_align(const std::string& text) {
  if (text == "none") return Align::none;
  if (text == "zoom") return Align::zoom;
  throw Error(field_text("align") + ": expected none or zoom, found \"" + text + "\"");
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
  auto in = [](const char* what, int v, const Range& range) {
    if (!range.contains(v))
      throw Error(std::string("model: ") + what + " must be in " + std::to_string(int(range.lo)) + "-" +
                  std::to_string(int(range.hi)) + ", found " + std::to_string(v));
  };
  const ModelConfigRanges& r = kModelConfigRanges;
  in("window", c.window, r.window);
  in("rows", c.rows, r.rows);
  in("cols", c.cols, r.cols);
  for (int ch : c.channels) in("channels", ch, r.channels);
  in("hidden", c.hidden, r.hidden);
  in("latent", c.latent, r.latent);
  in("context", c.context, r.context);
  if (c.contact && c.arch != Arch::frame)
    throw Error(std::string("model: a contact head needs the frame architecture, found ") + arch_name(c.arch));
}

std::string ModelFiles::path(const char* name) const { return (std::filesystem::path(dir) / name).string(); }

std::array<int, 2> pooled_size(const ModelConfig& c, int level) {
  std::array<int, 2> s{c.rows, c.cols};
  for (int k = 0; k < level; ++k) s = {(s[0] + 1) / 2, (s[1] + 1) / 2};
  return s;
}

std::array<float, 3> Normalisation::attributes(const BodySpec& body) const {
  return {body.sex == Sex::male ? 1.0f : 0.0f,
          float((body.height_cm - height_mean_cm) / height_std_cm),
          float((body.weight_kg - weight_mean_kg) / weight_std_kg)};
}

std::string baseline_warning(const nlohmann::json& metrics) {
  const auto number = [&](const char* key) {
    const auto it = metrics.find(key);
    return it != metrics.end() && it->is_number() ? it->get<double>() : NAN;
  };
  const double model = number("val_rmse_kpa"), zero = number("val_rmse_zero_kpa"), copy = number("val_rmse_copy_kpa");
  if (!std::isfinite(model) || !std::isfinite(zero) || !std::isfinite(copy)) return "";
  const auto beats = [&](double baseline) { return baseline <= 0 || model < kBaselineMargin * baseline; };
  if (beats(zero) && beats(copy)) return "";
  const bool zero_first = !beats(zero);
  return "validation RMSE " + fixed_text(model) + " kPa is no better than the " +
         (zero_first ? "all-zero" : "copy") + " baseline's " + fixed_text(zero_first ? zero : copy) + " kPa (" +
         (zero_first ? "copy" : "all-zero") + " baseline " + fixed_text(zero_first ? copy : zero) + " kPa)";
}

}  // namespace ptnet
