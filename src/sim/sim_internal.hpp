// Internal pieces of the simulator (see ptnet/sim.hpp).
//
// Dimension legend: T frames, R x C mat cells, S x S samples per cell.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/sim.hpp"

namespace ptnet::detail {

// Some rigs put the toe joint well above the metatarsal heads, so a flat
// foot's ankle -> toe bone is flatter than the canonical 20.8 degrees and the
// sole would stand on its heel. Per foot (left, right): the canonical rest
// pitch minus the median of the bone's pitch over planted frames
// (ankle slower than 0.05 m/s), rad, bounded to +/- 0.5; 0 with < 5 planted frames.
std::array<double, 2> foot_pitch_offsets(const Motion& motion);
// Rotates each toe joint about its ankle (down by the offset).
void correct_foot_pitch(Pose& pose, const std::array<double, 2>& offsets);
// The motion with its feet pitched by `offsets` (MotionPlacement::foot_pitch)
// when a foot's is more than ~2 degrees; unchanged otherwise (canonical motions).
Motion pitch_corrected(const Motion& motion, const std::array<double, 2>& offsets);

// The floor under a motion, frame by frame: the lower envelope over
// `window_s` (centred) of the sole planes of the feet that barely move
// (planted), smoothed, bounded to +/- max_m; [T], m. For a grounded motion
// on a level floor it is ~0; it removes a capture floor that drifts or tilts
// (a 4 m walk rising 4 cm). window_s 0: off (all 0).
std::vector<double> floor_track(const Motion& motion, const Body& body, double window_s, double max_m);

// The load of every frame and where the centre of mass asks it to act.
struct ComTrack {
  std::vector<double> load_n;         // [T] F = m (g + a_z), N
  std::vector<Eigen::Vector2d> zmp;   // [T] zero-moment point (world x, y), m
};
ComTrack com_track(const Motion& motion, const Body& body, double com_filter_hz);

// Gaussian smoothing of a series with sigma in samples, edges renormalised.
std::vector<double> gaussian_smooth(const std::vector<double>& x, double sigma);

// Rows [first, last] of a frame that may hold pressure; the others are 0
// (first > last: none).
struct RowSpan {
  int first = 0, last = -1;
};

// Depth-from-below rasteriser over the S x S sample grid of the mat, and the
// elastic-foundation load distribution. Reused across frames: no allocation
// after the first frames.
class Rasteriser {
 public:
  Rasteriser(const MatSpec& mat, int subsamples, double compliance_m, double max_sink_m);

  // Rasterises one posed body (mat coordinates): the lowest surface height
  // per sample, on and off the mat. With `trace`, also which surface (left
  // sole, right sole, other) and where along the sole each sample lies.
  void rasterise(const Body& body, const PosedBody& posed, bool trace);

  // Sinks the body into the foundation until it carries load_n (stiffness in
  // Pa per m of penetration) and writes each cell's pressure (kPa) into
  // frame[R * C], which must be all zero on entry (only the cells under the
  // contact are written); all zero when no surface is within the compliance band.
  // The pressures times the cell area sum to load_n over all contact, on and
  // off the mat. Clears the rasterised state. Fills *trace if given (needs
  // rasterise(..., true)).
  // With `target` (mat coordinates X, Y; m), the foundation tilts so that the
  // centre of pressure moves towards it (the penetration of each cell is
  // weighted by max(0, 1 + g . (r - c)), c the penetration centroid), at most
  // 0.6 standard deviations of the contact away from c (so that no contact
  // cell of a compact footprint is unloaded). Returns the rows it wrote.
  RowSpan distribute(double load_n, double stiffness_pa_per_m, const Eigen::Vector2d* target, float* frame,
                     FrameTrace* trace);

 private:
  enum Owner : unsigned char { kNone = 0, kLeftSole = 1, kRightSole = 2, kOther = 3 };
  void patch(const SoleSurface& sole, const SolePatch& p, Owner owner);
  // The samples [i0, i1] x [j0, j1] patch() may visit (any, on or off the
  // mat); false when it visits none.
  bool patch_box(const SoleSurface& sole, const SolePatch& p, int& i0, int& i1, int& j0, int& j1) const;
  // Whether any surface of the posed body may record a sample on the mat
  // (conservative: the bounding boxes of its patches and capsules).
  bool reaches_mat(const Body& body, const PosedBody& posed) const;
  void capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra, double rb);
  void sphere(double cx, double cy, double cz, double r);
  // Sample index range [lo, hi] covering mat coordinate range [x0, x1] along rows/cols.
  void row_range(double x0, double x1, int& lo, int& hi) const;
  void col_range(double y0, double y1, int& lo, int& hi) const;
  // Marks samples [i0, i1] x [j0, j1] (clipped to the mat) as written.
  void touch(int i0, int i1, int j0, int j1);
  // Records depth z at sample (i, j) (which may lie off the mat) for a
  // surface `owner` at sole coordinate u.
  void record(int i, int j, float z, Owner owner, float u) {
    if (!(z < reach_)) return;
    if (z < zlo_) zlo_ = z;
    if (i >= 0 && i < ns_rows_ && j >= 0 && j < ns_cols_) {
      const std::size_t k = std::size_t(i) * ns_cols_ + j;
      if (z < zbuf_[k]) {
        zbuf_[k] = z;
        if (trace_) owner_[k] = owner, ubuf_[k] = u;
      }
    } else {
      off_.push_back({z, i, j});
      if (trace_) off_owner_.push_back(owner), off_u_.push_back(u);
    }
  }
  void clear();

  MatSpec mat_;
  int s_;
  float band_, max_sink_, reach_;  // reach_: surfaces above this can never touch
  double ds_, half_l_, half_w_;
  int ns_rows_, ns_cols_;
  std::vector<float> zbuf_;  // [R S, C S] lowest surface height (m), +inf: none
  std::vector<unsigned char> hit_;  // [C S] distribute's scratch
  int di0_, di1_;                   // the sample rows written this frame (di0_ > di1_: none)
  std::vector<int> span0_, span1_;  // [R S] the columns [span0, span1] written in each sample row
  std::vector<int> cell0_, cell1_;  // [R] distribute's scratch: the cells of each row it may write
  float zlo_;                  // lowest recorded height this frame
  bool trace_ = false;
  std::vector<unsigned char> owner_;  // [R S, C S] with trace
  std::vector<float> ubuf_;           // [R S, C S] sole u with trace
  struct OffSample {
    float z;
    int i, j;  // sample indices, outside [0, R S) x [0, C S)
  };
  std::vector<OffSample> off_;        // samples off the mat
  std::vector<float> off_u_;
  std::vector<unsigned char> off_owner_;
};

// Applies the sensor model to one frame in place: [R * C] kPa. `scratch` has
// R * C floats; `rng` is the frame's noise stream state; the rows outside
// `pressed` are 0 on entry (distribute's span; default: any row).
void apply_sensor(const SensorModel& sensor, const MatSpec& mat, float* frame, float* scratch,
                  std::uint64_t& rng, RowSpan pressed = {0, 1 << 30});

}  // namespace ptnet::detail
