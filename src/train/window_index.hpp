// train/window_index.hpp (private to the train stage; tests include it
// through the stage's private include path): the lazy index of training and
// validation windows over source/target pairs, the normalisation fit and the
// bounded cache of whole sequences that batches are read from.
//
//   WindowIndex index = WindowIndex::build(source, WindowOptions{});
//   WindowRef w = index.train(i);                  // pair and first frame
//   SequenceCache cache(source, /*budget_mb=*/1024);
//   cache.read(index.pairs()[w.pair].source, w.start, 30, out);  // out [T, H, W] kPa
//
// Dimension legend: T window frames, H x W mat cells.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ptnet/train.hpp"

namespace ptnet {

// ------------------------------------------------------------ window index

struct WindowOptions {
  int window = kWindowFrames;         // frames per window
  int stride = 1;                 // frames between window starts
  double val_fraction = kValFraction;  // share of each motion's window starts held out
  std::uint64_t seed = 1;         // places the validation blocks
  bool identity_pairs = false;    // a motion on one body only gives the pair (a, a): fine-tuning
                                  // on real recordings (one subject per recording)
};

struct Pair {
  int source = 0, target = 0;     // indices into PressureSource::sequences()
  int motion = 0;                 // index into WindowIndex::motions()
};

struct WindowRef {
  int pair = 0;                   // index into WindowIndex::pairs()
  int start = 0;                  // first frame
};

class WindowIndex {
 public:
  // Throws Error ("data.h5: no training pairs: ...") when nothing qualifies.
  static WindowIndex build(const PressureSource& source, const WindowOptions& options);

  const std::vector<Pair>& pairs() const { return pairs_; }
  const std::vector<std::string>& motions() const { return motions_; }
  std::int64_t train_size() const { return train_total_; }
  std::int64_t val_size() const { return val_total_; }
  WindowRef train(std::int64_t i) const { return locate(i, train_ranges_, train_cum_); }
  WindowRef val(std::int64_t i) const { return locate(i, val_ranges_, val_cum_); }
  const WindowOptions& options() const { return options_; }
  // Sequences used by any pair (indices into sources().sequences()).
  std::vector<int> used_sequences() const;

 private:
  struct Range {
    int begin = 0, end = 0;  // window starts in [begin, end) (step stride)
  };
  using Ranges = std::vector<std::vector<Range>>;  // per motion
  WindowRef locate(std::int64_t i, const Ranges& ranges, const std::vector<std::int64_t>& cum) const;
  std::int64_t count(const std::vector<Range>& ranges) const;

  WindowOptions options_;
  std::vector<Pair> pairs_;
  std::vector<std::string> motions_;
  Ranges train_ranges_, val_ranges_;
  std::vector<std::int64_t> train_cum_, val_cum_;  // per pair, exclusive prefix sums
  std::int64_t train_total_ = 0, val_total_ = 0;
};

// Normalisation fitted on the training bodies (z-scores of height and weight)
// and on training frames (pressure scale = 99.9th percentile of the non-zero
// cells of up to `max_frames` evenly spaced frames, in kPa).
Normalisation fit_normalisation(const PressureSource& source, const WindowIndex& index,
                                int max_frames = 2000);

// Bounded cache of whole sequences (float32 kPa) for batch assembly.
class SequenceCache {
 public:
  SequenceCache(const PressureSource& source, double budget_mb);
  // Frames [start, start + count) of sequence `seq` into out[count, H, W], kPa.
  void read(int seq, int start, int count, float* out);
  double resident_mb() const;

 private:
  const PressureSource& source_;
  std::size_t budget_bytes_, used_bytes_ = 0;
  std::uint64_t clock_ = 0;
  struct Entry {
    std::vector<float> kpa;
    std::uint64_t last_use = 0;
  };
  std::map<int, Entry> entries_;
};

}  // namespace ptnet
