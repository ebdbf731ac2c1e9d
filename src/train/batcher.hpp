// train/batcher.hpp (private to the train stage): training and validation
// windows as tensors. A Batcher reads the windows of the lazy index through
// the sequence cache, aligns the source to the target body (Align::zoom),
// normalises and moves them to the device; the training augmentations crop
// around the pressure and mirror every second window.
//
//   Batcher batcher(source, index, norm, /*cache_mb=*/1024, torch::kCPU, Align::zoom);
//   Batch b = batcher.load(refs);           // b.x [N,T+2m,H,W], b.y [N,T,H,W]; b.sa, b.ta [N,A]
//   crop_to_pressure(b, 40);                // b.x, b.y -> [N,*,40,W]
//   mirror_every_second(b);
//
// Dimension legend: N windows in a batch, T window frames, m = the model's
// input_margin (context frames read beyond each end of the window; the
// sequence's end frame repeated where it has none), H x W mat cells,
// A = 3 attributes. Pressures are normalised (kPa / Normalisation::pressure_scale_kpa).
#pragma once

#include <array>
#include <vector>

#include "ptnet/model.hpp"
#include "ptnet/train.hpp"
#include "window_index.hpp"

namespace ptnet {

struct Batch {
  torch::Tensor x, y, sa, ta;  // network input [N,T+2m,H,W], truth [N,T,H,W]; attributes [N,A], [N,A]
  torch::Tensor src;           // the source windows as recorded [N,T,H,W] (x's centre frames unless aligned)
  int margin = 0;              // m
  torch::Tensor centre() const { return x.narrow(1, margin, y.size(1)); }  // x's T window frames
};

class Batcher {
 public:
  // For `model`'s input: its alignment and input_margin.
  Batcher(const PressureSource& src, const WindowIndex& index, const Normalisation& norm,
          double cache_mb, torch::Device device, const ModelConfig& model)
      : source_(src), index_(index), cache_(src, cache_mb), device_(device),
        inv_scale_(float(1.0 / norm.pressure_scale_kpa)), align_(model.align), margin_(input_margin(model)) {
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
  int margin_;
  std::vector<std::array<float, 3>> attrs_;
  const BodySpec& body_of(int seq) const { return source_.body(source_.sequences()[std::size_t(seq)].body_id); }
  // Frames [start - margin_, start + count + margin_) of `seq` into out, the
  // sequence's first and last frame repeated beyond its ends.
  void read_with_margin(int seq, int start, int count, float* out);
};

// Training crops for a fully convolutional network (Arch::frame): each
// window cut to `rows` mat rows centred on its pressure (input and truth), so
// that the work goes where the feet are. b.x, b.y [N,*,H,W] -> [N,*,rows,W].
void crop_to_pressure(Batch& b, int rows);

// TrainOptions::mirror: windows 1, 3, 5, ... of a micro-batch (the epoch's
// order is shuffled) mirrored through the mat's long axis, input and truth.
void mirror_every_second(Batch& b);

}  // namespace ptnet
