// train/batcher.hpp (private to the train stage): training and validation
// windows as tensors. A Batcher reads the windows of the lazy index through
// the sequence cache, aligns the source to the target body (Align::zoom),
// normalises and moves them to the device; the training augmentations crop
// around the pressure and mirror every second window.
//
//   Batcher batcher(source, index, norm, /*cache_mb=*/1024, torch::kCPU, Align::zoom);
//   Batch b = batcher.load(refs);           // b.x, b.y [N,T,H,W]; b.sa, b.ta [N,A]
//   crop_to_pressure(b, 40);                // b.x, b.y -> [N,T,40,W]
//   mirror_every_second(b);
//
// Dimension legend: N windows in a batch, T window frames, H x W mat cells,
// A = 3 attributes. Pressures are normalised (kPa / Normalisation::pressure_scale_kpa).
#pragma once

#include <array>
#include <vector>

#include "ptnet/model.hpp"
#include "ptnet/train.hpp"
#include "window_index.hpp"

namespace ptnet {

struct Batch {
  torch::Tensor x, y, sa, ta;  // network input, truth [N,T,H,W]; attributes [N,A], [N,A]
  torch::Tensor src;           // the source windows as recorded [N,T,H,W] (= x unless aligned)
};

class Batcher {
 public:
  Batcher(const PressureSource& src, const WindowIndex& index, const Normalisation& norm,
          double cache_mb, torch::Device device, Align align)
      : source_(src), index_(index), cache_(src, cache_mb), device_(device),
        inv_scale_(float(1.0 / norm.pressure_scale_kpa)), align_(align) {
    for (const auto& s : src.sequences()) attrs_.push_back(norm.attributes(src.body(s.body_id)));
  }

  // The windows `refs` as tensors on the device, divided by the pressure
  // scale; with_source: also keep the unaligned source windows (for the
  // baselines) in b.src.
  Batch load(const std::vector<WindowRef>& refs, bool with_source = false);

  // Windows per source attribute ratio (for the weight-scale baseline).
  double weight_ratio(const WindowRef& r) const {
    const auto& seqs = source_.sequences();
    const Pair& p = index_.pairs()[std::size_t(r.pair)];
    return source_.body(seqs[p.target].body_id).weight_kg / source_.body(seqs[p.source].body_id).weight_kg;
  }

 private:
  const PressureSource& source_;
  const WindowIndex& index_;
  SequenceCache cache_;
  torch::Device device_;
  float inv_scale_;
  Align align_;
  std::vector<std::array<float, 3>> attrs_;
  const BodySpec& body_of(int seq) const { return source_.body(source_.sequences()[std::size_t(seq)].body_id); }
};

// Training crops for a fully convolutional network (Arch::frame): each
// window cut to `rows` mat rows centred on its pressure (input and truth), so
// that the work goes where the feet are. b.x, b.y [N,T,H,W] -> [N,T,rows,W].
void crop_to_pressure(Batch& b, int rows);

// TrainOptions::mirror: windows 1, 3, 5, ... of a micro-batch (the epoch's
// order is shuffled) mirrored through the mat's long axis, input and truth.
void mirror_every_second(Batch& b);

}  // namespace ptnet
