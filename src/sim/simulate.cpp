// simulate(): placement, depth, contact, load and sensor, frame by frame.
#include <algorithm>
#include <cmath>

#include "core/hash.hpp"
#include "ptnet/error.hpp"
#include "sim_internal.hpp"

namespace ptnet {

Placement parse_placement(const std::string& text) {
  if (text == "fixed") return Placement::fixed;
  if (text == "follow") return Placement::follow;
  throw Error("placement '" + text + "' is not fixed or follow");
}

const char* placement_name(Placement placement) {
  return placement == Placement::follow ? "follow" : "fixed";
}

SensorModel ideal_sensor() {
  SensorModel s;
  s.crosstalk = 0;
  s.saturation_kpa = 1e9;
  s.noise_sd_kpa = 0;
  s.threshold_kpa = 0;
  s.quantum_kpa = 0;
  return s;
}

namespace {

void check_options(const SimOptions& o) {
  if (o.mat.rows < 1 || o.mat.cols < 1 || !(o.mat.pitch_m > 0))
    throw Error("simulate: mat must have rows, cols >= 1 and pitch_m > 0");
  if (o.subsamples < 1 || o.subsamples > 16) throw Error("simulate: subsamples must be 1-16");
  if (!(o.compliance_m > 0)) throw Error("simulate: compliance_m must be > 0");
  if (!(o.stiffness_kpa_per_mm > 0)) throw Error("simulate: stiffness_kpa_per_mm must be > 0");
  if (!(o.max_sink_m > 0)) throw Error("simulate: max_sink_m must be > 0");
  if (!(o.floor_window_s >= 0)) throw Error("simulate: floor_window_s must be >= 0");
  const auto& s = o.sensor;
  if (!(s.crosstalk >= 0 && s.crosstalk < 0.25)) throw Error("simulate: crosstalk must be in [0, 0.25)");
  if (!(s.saturation_kpa > 0) || !(s.noise_sd_kpa >= 0) || !(s.threshold_kpa >= 0) || !(s.quantum_kpa >= 0))
    throw Error("simulate: sensor saturation must be > 0; noise, threshold, quantum >= 0");
}

}  // namespace

PressureSequence simulate(const Motion& motion, const Body& body, const SimOptions& options) {
  return simulate(motion, body, options, nullptr);
}

PressureSequence simulate(const Motion& motion, const Body& body, const SimOptions& options,
                          std::vector<FrameTrace>* trace) {
  check_options(options);
  if (motion.size() == 0) throw Error("simulate: motion '" + motion.name + "' has no frames");
  return simulate(motion, body, options, place_motion(motion, options), trace);
}

namespace {

// Readings of T frames that hold none yet: each grows by one zeroed frame
// at a time (Foundation::distribute writes only the contact) into memory
// reserved for all T, so that a frame is zeroed in the cache just before
// it is written, not all at once.
std::vector<PressureSequence> empty_readings(const MatSpec& mat, int T, double fps, std::size_t n) {
  std::vector<PressureSequence> reads;
  for (std::size_t k = 0; k < n; ++k) {
    reads.emplace_back(mat, 0, fps);
    reads.back().kpa.reserve(std::size_t(T) * mat.cells());
  }
  return reads;
}

// Frame t's pose in mat coordinates (along the mat, across it, above the
// floor), its feet lifted.
Pose mat_pose(const Pose& pose, const MotionPlacement& place, int t, double floor) {
  Pose local;
  for (int j = 0; j < kJointCount; ++j) {
    const Eigen::Vector2d d = pose[j].head<2>() - place.centre[std::size_t(t)];
    local[j] = Eigen::Vector3d(place.axis.dot(d), place.left.dot(d), pose[j].z() - floor);
  }
  detail::lift_feet(local, place.foot_lift);
  return local;
}

// simulate() read by the sensor once per seed: the pressure of each frame is
// simulated once, copied to every reading, and each reading gets the sensor
// model with its own noise stream (one state per seed, advanced frame by
// frame exactly as a single simulate() advances it).
std::vector<PressureSequence> simulate_seeds(const Motion& input, const Body& body, const SimOptions& options,
                                             const MotionPlacement& place, std::vector<FrameTrace>* trace,
                                             const std::vector<std::uint64_t>& seeds) {
  check_options(options);
  if (input.size() == 0) throw Error("simulate: motion '" + input.name + "' has no frames");
  if (place.centre.size() != std::size_t(input.size()) || !(place.floor.empty() || place.floor.size() == place.centre.size()))
    throw Error("simulate: motion '" + input.name + "' has " + std::to_string(input.size()) +
                " frames but its placement " + std::to_string(place.centre.size()) + " centres and " +
                std::to_string(place.floor.size()) + " floor heights");
  const Motion motion = detail::pitch_corrected(input, place.foot_pitch);
  const int T = motion.size();
  const MatSpec& mat = options.mat;
  std::vector<PressureSequence> reads = empty_readings(mat, T, motion.fps, seeds.size());
  if (trace) trace->assign(std::size_t(T), FrameTrace{});

  const detail::FloorSupport support = detail::floor_support(motion, body, place, options.compliance_m);
  detail::ComTrack com = detail::com_track(motion, body, options.com_filter_hz, &support.contact);
  const std::vector<double> share = detail::seat_share(support, com.zmp, body.sole().width_m, motion.fps);
  const std::vector<double> floor = place.floor.empty() ? std::vector<double>(std::size_t(T), 0.0) : place.floor;
  detail::Rasteriser raster(mat, options.subsamples, options.compliance_m + options.max_sink_m);
  detail::Foundation foundation(raster.depth().grid, options.compliance_m, options.max_sink_m);
  std::vector<float> scratch(mat.cells());
  std::vector<std::uint64_t> rng;
  for (std::uint64_t seed : seeds) rng.push_back(seed ^ 0x5bd1e9955bd1e995ULL);
  const double stiffness = options.stiffness_kpa_per_mm * 1e6;  // kPa/mm -> Pa/m

  for (int t = 0; t < T; ++t) {
    const Eigen::Vector2d& c = place.centre[t];
    for (PressureSequence& r : reads) r.kpa.resize(std::size_t(t + 1) * mat.cells());
    float* frame = reads[0].frame(t);
    const double load = share[std::size_t(t)] * com.load_n[std::size_t(t)];
    FrameTrace* ft = trace ? &(*trace)[std::size_t(t)] : nullptr;
    // Without a load the frame reads 0 (distribute returns at once): with
    // no trace to fill, nothing is rasterised.
    detail::RowSpan pressed;
    if (ft || load > 0) {
      const Pose local = mat_pose(motion.frames[t], place, t, floor[std::size_t(t)]);
      raster.rasterise(body, pose_body(body, local), ft != nullptr);
      const Eigen::Vector2d d = com.zmp[std::size_t(t)] - c;
      const Eigen::Vector2d zmp(place.axis.dot(d), place.left.dot(d));
      pressed = foundation.distribute(raster.depth(), load, stiffness, options.balance_moments ? &zmp : nullptr,
                                      frame, ft);
    }
    if (ft && raster.depth().zlo < options.compliance_m) ft->carried_n = com.load_n[std::size_t(t)] - load;
    // The other readings' frames are all zero outside the pressed rows too.
    const std::size_t first = std::size_t(std::max(0, pressed.first)) * std::size_t(mat.cols);
    const std::size_t end = std::size_t(std::min(mat.rows, pressed.last + 1)) * std::size_t(mat.cols);
    for (std::size_t k = 1; k < reads.size() && first < end; ++k)
      std::copy(frame + first, frame + end, reads[k].frame(t) + first);
    for (std::size_t k = 0; k < reads.size(); ++k)
      detail::apply_sensor(options.sensor, mat, reads[k].frame(t), scratch.data(), rng[k], pressed);
  }
  return reads;
}

}  // namespace

PressureSequence simulate(const Motion& input, const Body& body, const SimOptions& options,
                          const MotionPlacement& place, std::vector<FrameTrace>* trace) {
  return std::move(simulate_seeds(input, body, options, place, trace, {options.seed})[0]);
}

std::vector<PressureSequence> simulate_reads(const Motion& motion, const Body& body, const SimOptions& options,
                                             const MotionPlacement& placement,
                                             const std::vector<std::uint64_t>& seeds, std::vector<FrameTrace>* trace) {
  if (seeds.empty()) return {};
  return simulate_seeds(motion, body, options, placement, trace, seeds);
}

std::uint64_t sequence_seed(std::uint64_t seed, const std::string& name) {
  const std::uint64_t h = fnv1a(name);
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (h | 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t floor_seed(std::uint64_t seed, const std::string& name) { return sequence_seed(seed, name + "/floor"); }

}  // namespace ptnet
