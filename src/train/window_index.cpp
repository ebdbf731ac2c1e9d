// Lazy (pair, start) window index with a per-motion time split, the
// normalisation fit, and the bounded sequence cache. No Torch.
#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "core/hash.hpp"
#include "ptnet/error.hpp"
#include "ptnet/train.hpp"
#include "source.hpp"
#include "window_index.hpp"

namespace ptnet {

WindowIndex WindowIndex::build(const PressureSource& source, const WindowOptions& options) {
  if (options.window < 1) throw Error("window must be >= 1, found " + std::to_string(options.window));
  if (options.stride < 1) throw Error("stride must be >= 1, found " + std::to_string(options.stride));
  if (!(options.val_fraction >= 0 && options.val_fraction < 1))
    throw Error("validation fraction must be in [0, 1)");
  WindowIndex index;
  index.options_ = options;
  const auto& seqs = source.sequences();

  // Training sequences grouped by motion_id (std::map: sorted, deterministic).
  std::map<std::string, std::vector<int>> groups;
  int eligible = 0;
  for (int i = 0; i < int(seqs.size()); ++i) {
    if (!is_training_sequence(source.body(seqs[i].body_id), seqs[i])) continue;
    ++eligible;
    groups[seqs[i].motion_id].push_back(i);
  }
  int short_motions = 0;
  for (const auto& [motion, members] : groups) {
    int frames = seqs[members[0]].frames;
    for (int m : members) frames = std::min(frames, seqs[m].frames);
    const int starts = frames - options.window + 1;
    if (starts < 1) {
      ++short_motions;
      continue;
    }
    std::vector<Pair> pairs;
    for (int a : members)
      for (int b : members)
        if (seqs[a].body_id != seqs[b].body_id || (options.identity_pairs && members.size() == 1))
          pairs.push_back({a, b, int(index.motions_.size())});
    if (pairs.empty()) continue;

    // Validation block of ~val_fraction of the starts, at a seeded position;
    // training starts keep `window - 1` frames away from it on both sides.
    std::vector<Range> train, val;
    int n_val = options.val_fraction > 0 ? std::max(1, int(std::lround(starts * options.val_fraction))) : 0;
    const int gap = options.window - 1;
    if (n_val > 0 && starts >= n_val + gap + 1) {
      // Anywhere when there is room for training windows on both sides,
      // else at the end (one gap only).
      std::mt19937_64 rng(options.seed ^ fnv1a(motion, Fnv1a::kTruncatedBasis));
      const int v0 = starts >= 3 * (n_val + gap) ? std::uniform_int_distribution<int>(0, starts - n_val)(rng)
                                                 : starts - n_val;
      val.push_back({v0, v0 + n_val});
      if (v0 - gap > 0) train.push_back({0, v0 - gap});
      if (v0 + n_val + gap < starts) train.push_back({v0 + n_val + gap, starts});
    } else {
      train.push_back({0, starts});  // too short to split: training only
    }
    index.motions_.push_back(motion);
    index.train_ranges_.push_back(train);
    index.val_ranges_.push_back(val);
    for (const auto& p : pairs) index.pairs_.push_back(p);
  }
  if (index.pairs_.empty())
    throw Error::in(source.path(),
                    "no training pairs: need one motion_id (take 1) on at least two retargeted bodies, "
                    "with at least " + std::to_string(options.window) + " frames; found " +
                        std::to_string(seqs.size()) + " sequences, " + std::to_string(eligible) +
                        " retargeted take-1" +
                        (short_motions ? ", " + std::to_string(short_motions) + " motions too short" : ""));
  for (const auto& p : index.pairs_) {
    index.train_cum_.push_back(index.train_total_);
    index.val_cum_.push_back(index.val_total_);
    index.train_total_ += index.count(index.train_ranges_[p.motion]);
    index.val_total_ += index.count(index.val_ranges_[p.motion]);
  }
  return index;
}

std::int64_t WindowIndex::count(const std::vector<Range>& ranges) const {
  std::int64_t n = 0;
  for (const auto& r : ranges)
    if (r.end > r.begin) n += (r.end - r.begin + options_.stride - 1) / options_.stride;
  return n;
}

WindowRef WindowIndex::locate(std::int64_t i, const Ranges& ranges,
                              const std::vector<std::int64_t>& cum) const {
  const std::int64_t total = &cum == &train_cum_ ? train_total_ : val_total_;
  if (i < 0 || i >= total) throw Error("window index " + std::to_string(i) + " out of range");
  // Last pair whose prefix sum is <= i (pairs with no windows share a prefix).
  auto it = std::upper_bound(cum.begin(), cum.end(), i);
  int p = int(it - cum.begin()) - 1;
  std::int64_t offset = i - cum[p];
  for (const auto& r : ranges[pairs_[p].motion]) {
    const std::int64_t n = r.end > r.begin ? (r.end - r.begin + options_.stride - 1) / options_.stride : 0;
    if (offset < n) return {p, int(r.begin + offset * options_.stride)};
    offset -= n;
  }
  throw Error("window index inconsistent");  // unreachable
}

std::vector<int> WindowIndex::used_sequences() const {
  std::set<int> used;
  for (const auto& p : pairs_) {
    used.insert(p.source);
    used.insert(p.target);
  }
  return {used.begin(), used.end()};
}

Normalisation fit_normalisation(const PressureSource& source, const WindowIndex& index, int max_frames) {
  Normalisation n;
  const auto& seqs = source.sequences();
  const std::vector<int> used = index.used_sequences();
  std::set<std::string> body_ids;
  for (int s : used) body_ids.insert(seqs[s].body_id);
  double hs = 0, hs2 = 0, ws = 0, ws2 = 0;
  for (const auto& id : body_ids) {
    const BodySpec& b = source.body(id);
    hs += b.height_cm, hs2 += b.height_cm * b.height_cm;
    ws += b.weight_kg, ws2 += b.weight_kg * b.weight_kg;
  }
  const double k = double(body_ids.size());
  n.height_mean_cm = hs / k;
  n.weight_mean_kg = ws / k;
  n.height_std_cm = std::sqrt(std::max(0.0, hs2 / k - n.height_mean_cm * n.height_mean_cm));
  n.weight_std_kg = std::sqrt(std::max(0.0, ws2 / k - n.weight_mean_kg * n.weight_mean_kg));
  if (n.height_std_cm < 1) n.height_std_cm = 1;  // one body, or identical bodies
  if (n.weight_std_kg < 1) n.weight_std_kg = 1;

  // Pressure scale: 99.9th percentile of non-zero cells of evenly spaced frames.
  std::int64_t total_frames = 0;
  for (int s : used) total_frames += seqs[s].frames;
  const double step = std::max(1.0, double(total_frames) / std::max(1, max_frames));
  std::vector<float> frame(std::size_t(source.mat().cells())), values;
  double next = 0;
  std::int64_t base = 0;
  for (int s : used) {
    for (; next < base + seqs[s].frames; next += step) {
      source.read(seqs[s].name, int(next - base), 1, frame.data());
      for (float v : frame)
        if (v > 0) values.push_back(v);
    }
    base += seqs[s].frames;
  }
  if (!values.empty()) {
    n.min_reading_kpa = *std::min_element(values.begin(), values.end());
    auto q = values.begin() + std::ptrdiff_t(double(values.size() - 1) * 0.999);
    std::nth_element(values.begin(), q, values.end());
    if (*q > 0 && std::isfinite(*q)) n.pressure_scale_kpa = *q;
  }
  return n;
}

SequenceCache::SequenceCache(const PressureSource& source, double budget_mb)
    : source_(source), budget_bytes_(std::size_t(std::max(0.0, budget_mb) * 1024 * 1024)) {}

void SequenceCache::read(int seq, int start, int count, float* out) {
  const auto& meta = source_.sequences()[std::size_t(seq)];
  const std::size_t cells = std::size_t(source_.mat().cells());
  auto it = entries_.find(seq);
  if (it == entries_.end()) {
    const std::size_t bytes = std::size_t(meta.frames) * cells * sizeof(float);
    if (bytes > budget_bytes_) {  // never fits: read the window directly
      source_.read(meta.name, start, count, out);
      return;
    }
    while (used_bytes_ + bytes > budget_bytes_ && !entries_.empty()) {
      auto lru = std::min_element(entries_.begin(), entries_.end(), [](const auto& a, const auto& b) {
        return a.second.last_use < b.second.last_use;
      });
      used_bytes_ -= lru->second.kpa.size() * sizeof(float);
      entries_.erase(lru);
    }
    Entry e;
    e.kpa.resize(std::size_t(meta.frames) * cells);
    source_.read(meta.name, 0, meta.frames, e.kpa.data());
    used_bytes_ += bytes;
    it = entries_.emplace(seq, std::move(e)).first;
  }
  it->second.last_use = ++clock_;
  if (start < 0 || start + count > meta.frames)
    throw Error::in(source_.path(), meta.name + ": window outside the sequence");
  std::copy_n(it->second.kpa.data() + std::size_t(start) * cells, std::size_t(count) * cells, out);
}

double SequenceCache::resident_mb() const { return double(used_bytes_) / (1024.0 * 1024.0); }

}  // namespace ptnet
