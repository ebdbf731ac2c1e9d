// ptnet/model_config.hpp: the PressureTransferNet hyper-parameters and the
// model directory's config.json, without any Torch include (the CLI, the
// transfer API and the evaluation stage read it).
//
//   ptnet::ModelConfig c = ptnet::ModelConfig::paper();   // 64/128/256, latent 128
//   c.channels = {16, 32, 64};                            // a smaller network
//   ptnet::validate(c);                                   // throws Error if impossible
//   ptnet::ModelDir dir = ptnet::read_model_dir("model/");  // config.json, validated
//   auto attrs = dir.norm.attributes(body);               // {sex, z(height), z(weight)}
//
// A model directory holds:
//   config.json    format "ptnet-model", version 1: architecture, window, mat,
//                  normalisation, training-data digest, options, final metrics
//   model.pt       the best weights (by validation loss)
//   checkpoint.pt  the last epoch: weights, optimizer, epoch, RNG, best val,
//                  patience counter, history (for --resume)
//   history.csv    epoch,train_loss,val_loss,lr,seconds (one row per epoch)
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "ptnet/body_spec.hpp"
#include "ptnet/error.hpp"
#include "ptnet/paper.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

inline constexpr int kAttributes = 3;     // sex, height, weight
inline constexpr int kHidden = 128;       // width of the FC layer after the encoder's convolutions
inline constexpr int kLatent = 128;       // width of the latent after the source attributes
inline constexpr int kPoolLevels = 3;     // encoder blocks (each halves rows and cols, rounding up)
inline constexpr std::array<int, 3> kPaperChannels{64, 128, 256};  // conv widths, blocks 1-3
inline constexpr std::array<int, 3> kFastChannels{16, 32, 64};     // conv widths of the fast preset
inline constexpr const char* kModelFormat = "ptnet-model";
inline constexpr int kModelVersion = 1;
inline constexpr std::uint64_t kMaxConfigBytes = std::uint64_t(16) << 20;  // config.json: 16 MiB

// faithful: the paper's network (decoder unpools with the encoder's max-pool
// indices). skip: the same plus U-Net skip connections (each decoder block
// also sees the encoder block's feature map at its resolution). residual:
// skip, and the network predicts a correction added to its input window
// (output = ReLU(input + decoder)): an untrained residual model is the copy
// baseline, training learns what changes from the source body to the target.
// frame (ours): a conditional U-Net applied to each frame on its own (with
// `context` neighbouring frames of the window as extra input channels), at
// full resolution, the body attributes injected at every scale (FiLM); the
// output is a correction added to the frame (zero-initialised). The window is
// only a batch of frames to it: any window length works, so the fast preset
// trains on single frames (window 1). With `contact` it also predicts which
// cells are in contact (ModelConfig::contact).
enum class Arch { faithful, skip, residual, frame };

// What the network sees of the source window. none: the recorded maps (the
// paper). zoom: the maps aligned to the target body first, zoomed by the
// height ratio about the mat centre and scaled by the weight ratio over the
// area ratio (zoom_about_centre in pressure.hpp), so that the network learns
// only what the body-scale geometry does not explain.
enum class Align { none, zoom };
Align parse_align(const std::string& text);  // "none" | "zoom"; throws Error
const char* align_name(Align align);
Arch parse_arch(const std::string& text);  // "faithful" | "skip" | "residual" | "frame"; throws Error
const char* arch_name(Arch arch);

struct ModelConfig {
  Arch arch = Arch::faithful;
  Align align = Align::none;
  int window = kWindowFrames;                  // frames per window = input/output channels
  int rows = kMatRows;                     // mat rows (H)
  int cols = kMatCols;                     // mat cols (W)
  std::array<int, 3> channels = kPaperChannels;  // conv widths of encoder blocks 1-3
  int hidden = kHidden;                    // FC after the flattened conv features
  int latent = kLatent;                    // FC after concatenating the source attributes
  int context = 0;                         // Arch::frame: neighbouring frames on each side as input (input_margin)
  // Arch::frame: a second output channel, the logit of "this cell is in
  // contact" (trained with a cross-entropy loss beside the pressure loss); the
  // output is 0 where the logit is < 0 and at least the data's smallest
  // reading (the sensor's activation threshold) where it is > 0.
  bool contact = false;
  // Left-right mirror averaging at inference: the output is the mean of the
  // network on the input and, mirrored back, on the input mirrored through the
  // mat's long axis (columns c <-> cols - 1 - c). Bodies are left-right
  // symmetric, so both are estimates of one map. Training decides it on the
  // validation windows (TrainOptions::mirror); mirror_averaged() (model.hpp).
  bool mirror = false;
  static ModelConfig paper() { return {}; }
  static ModelConfig fast() {
    ModelConfig c;
    c.channels = kFastChannels;
    return c;
  }
};

// Frames of input beyond the output at each end of a window: an Arch::frame
// network reads `context` frames before and after every frame it transfers,
// so its input window is window + 2 margin frames (the sequence's end frames
// repeated where it has none) and its output the window.
inline int input_margin(const ModelConfig& c) { return c.arch == Arch::frame ? c.context : 0; }

// The values validate() accepts (`ptnet train`'s validators read them too).
struct ModelConfigRanges {
  Range window{1, 10000}, rows{1, 100000}, cols{1, 100000}, channels{1, 4096}, hidden{1, 1 << 16},
      latent{1, 1 << 16}, context{0, 16};
};
inline constexpr ModelConfigRanges kModelConfigRanges{};

// Throws Error ("model: channels must be in 1-4096, found 0") for impossible values.
void validate(const ModelConfig& config);

// The cost model (src/model/cost_model.cpp).
// Closed-form number of trainable parameters (equals the module's count).
std::int64_t parameter_count(const ModelConfig& config);
// Bytes a model needs in memory (an estimate, for the check before
// allocating): float32 weights, with `training` their gradients and Adam's
// two moments, plus the activations of `batch` windows (x 2 for backward).
std::uint64_t model_memory_bytes(const ModelConfig& config, int batch, bool training);

// Attribute and pressure normalisation, fitted on the training bodies/frames.
struct Normalisation {
  double pressure_scale_kpa = 1;  // network pressure = kPa / scale
  double height_mean_cm = 170, height_std_cm = 10;
  double weight_mean_kg = 70, weight_std_kg = 10;
  // Output cells below this are set to 0 (kPa; 0 = off): the transferred map's
  // activation threshold, fitted after training on the validation windows so
  // that the predicted contact area matches the truth's (docs/model.md).
  double contact_threshold_kpa = 0;
  // The smallest non-zero reading of the training frames (kPa; the sensor's
  // activation threshold): a contact-head model's smallest contact value.
  double min_reading_kpa = 0;
  // {sex (0 female, 1 male), z-scored height, z-scored weight}
  std::array<float, 3> attributes(const BodySpec& body) const;
};

// The model folder's file names, written once (the folder is described at
// the top of this header).
struct ModelFiles {
  static constexpr const char* kConfig = "config.json";        // architecture, normalisation, ...
  static constexpr const char* kWeights = "model.pt";          // the best weights
  static constexpr const char* kCheckpoint = "checkpoint.pt";  // the last epoch (resume)
  static constexpr const char* kHistory = "history.csv";       // one row per epoch
  static constexpr const char* kAll[] = {kConfig, kWeights, kCheckpoint, kHistory};

  std::string dir;  // the folder
  explicit ModelFiles(std::string folder) : dir(std::move(folder)) {}
  std::string path(const char* name) const;  // dir/name
  std::string config() const { return path(kConfig); }
  std::string weights() const { return path(kWeights); }
  std::string checkpoint() const { return path(kCheckpoint); }
  std::string history() const { return path(kHistory); }
};

// Everything config.json holds.
struct ModelDir {
  std::string path;        // the folder
  ModelConfig model;
  Normalisation norm;
  MatSpec mat;
  double fps = kFps;
  nlohmann::json data;     // training data: path, digest, counts
  nlohmann::json options;  // training options
  nlohmann::json metrics;  // final metrics
  // Digests of the weights (weights_digest, model.hpp) written with them:
  // {"model.pt": "HEX", "checkpoint.pt": {"epoch": N, "digest": "HEX"}};
  // checked by transfer, train --init and --resume. Empty in models written
  // before ptnet 0.1 kept digests (only the archive CRCs are checked then).
  nlohmann::json integrity;
};

// A model no better than doing nothing: its validation RMSE (config.json's
// metrics "val_rmse_kpa") is not below kBaselineMargin x the all-zero
// baseline's ("val_rmse_zero_kpa") or the copy baseline's
// ("val_rmse_copy_kpa"). Returns the warning, naming both figures
// ("validation RMSE 13.820 kPa is no better than the all-zero baseline's
// 13.820 kPa (copy baseline 15.104 kPa)"); "" when the model beats both, or
// the metrics lack them. A baseline of RMSE 0 (the truth itself: a copy of
// identity pairs, or empty frames) is no bar. `train` reports it (an Error
// with TrainOptions::strict), `evaluate` repeats it.
inline constexpr double kBaselineMargin = 0.99;  // beat a baseline by at least 1 %
std::string baseline_warning(const nlohmann::json& metrics);

// The digests in config.json (src/model/integrity_record.cpp; the digest: integrity.cpp).
// The digest recorded in dir.integrity for `file` ("model.pt",
// "checkpoint.pt"), "" when none; `epoch` gets the checkpoint's epoch (-1).
std::string recorded_digest(const ModelDir& dir, const std::string& file, int* epoch = nullptr);
// Records `digest` for `file` (with the checkpoint's epoch when >= 0).
void record_digest(ModelDir& dir, const std::string& file, const std::string& digest, int epoch = -1);

// config.json (src/model/config_json.cpp).
nlohmann::json to_json(const ModelConfig& config);
nlohmann::json to_json(const ModelDir& dir);
// Reads and validates DIR/config.json (format, version, fields); throws Error
// naming the file ("model/config.json: missing field \"normalisation\"").
ModelDir read_model_dir(const std::string& dir);

}  // namespace ptnet
