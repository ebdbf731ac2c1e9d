// ptnet/stream.hpp: live transfer, frame by frame (no Torch in this header).
//
//   ptnet::Stream live("model/", source, target);     // as ptnet::Transfer
//   std::vector<float> out(live.max_output_frames() * live.frame_cells());
//   while (read(frame)) {                             // rows x cols kPa, row-major
//     int ready = live.push(frame.data(), out.data());
//     write(out.data(), ready * live.frame_cells());  // 0, 1, or (once) K frames
//   }
//
// A causal sliding window of K = the model's window frames: frame t is
// transferred as soon as the window of frames t-K+1 .. t is complete, and its
// output is that window's last output frame. The first window completes at
// frame K-1 and gives its K output frames at once; every later frame gives
// one. A one-frame model (the fast and full presets: window 1) answers every
// frame at once, and equals the offline transfer (Transfer::run) within float
// rounding. A window model differs from the offline transfer, which averages
// the windows covering a frame (they are in the future for a live frame):
// frame t is what Transfer::run gives for frames t-K+1 .. t alone
// (docs/model.md, "Live streaming").
#pragma once

#include <memory>
#include <string>

#include "ptnet/body_spec.hpp"
#include "ptnet/model_config.hpp"

namespace ptnet {

struct StreamOptions {
  int threads = 1;            // torch::set_num_threads (0 leaves the default)
  bool raw = false;           // true: skip the model's fitted contact threshold
  std::string input_name = "stream";  // names the input in errors
};

class Stream {
 public:
  // Throws Error as Transfer (model folder, weights), for a source or target
  // body out of range, and for a model that reads frames ahead (context > 0:
  // a stream has no future frames).
  Stream(const std::string& model_dir, const BodySpec& source, const BodySpec& target,
         const StreamOptions& options = {});
  ~Stream();
  Stream(Stream&&) noexcept;
  Stream& operator=(Stream&&) noexcept;

  const ModelDir& model() const;
  int frame_cells() const;        // rows x cols
  int max_output_frames() const;  // K: the most frames one push() gives
  long long frames_in() const;    // frames pushed so far

  // One input frame (frame_cells() floats, kPa) -> the output frames it
  // completes, written to `out` (room for max_output_frames() frames); returns
  // how many. Throws Error "NAME: pressure frames: non-finite value (NaN or
  // Inf) in frame N" (check_finite; the stream is then unchanged).
  int push(const float* frame, float* out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ptnet
