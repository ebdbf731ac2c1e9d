// ptnet/transfer.hpp: run a trained PressureTransferNet on a whole sequence
// (no Torch in this header).
//
//   ptnet::Transfer net("model/");                      // config.json + model.pt, validated
//   ptnet::BodySpec src{"s1", ptnet::Sex::female, 165, 60};
//   ptnet::BodySpec dst{"t", ptnet::Sex::male, 185, 95};
//   ptnet::PressureSequence out = net.run(recorded, src, dst);   // same length, kPa
//
// A sequence of T >= window frames is cut into windows every `stride` frames
// (plus one ending at the last frame), each window is transferred, and every
// output frame is the average of the windows covering it; cells below the
// model's fitted contact threshold (config.json, docs/model.md) are then 0.
#pragma once

#include <memory>
#include <string>

#include "ptnet/body_spec.hpp"
#include "ptnet/error.hpp"
#include "ptnet/model_config.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

struct TransferOptions {
  int stride = 5;            // frames between window starts (1 = every window)
  int batch = 64;            // windows per forward pass
  int threads = 0;           // torch::set_num_threads; 0 leaves the default
  std::string device = "cpu";
  bool raw = false;          // true: skip the model's fitted contact threshold
};

// The values TransferOptions accepts (Transfer's check; the CLI's validators).
struct TransferOptionsRanges {
  Range stride{1, 100000}, batch{1, 1 << 20};
};
inline constexpr TransferOptionsRanges kTransferOptionsRanges;

class Transfer {
 public:
  // Throws Error naming the file: missing folder, bad config.json, weights
  // that do not match the architecture.
  explicit Transfer(const std::string& model_dir, const TransferOptions& options = {});
  ~Transfer();
  Transfer(Transfer&&) noexcept;
  Transfer& operator=(Transfer&&) noexcept;

  const ModelDir& model() const;

  // src [T, H, W] kPa recorded on `source` -> [T, H, W] kPa for `target`.
  // Throws Error if the mat differs from the model's, T < window, or an
  // attribute is out of range.
  PressureSequence run(const PressureSequence& src, const BodySpec& source,
                       const BodySpec& target) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ptnet
