// Internal pieces of the simulator (see ptnet/sim.hpp): foot pitch and
// floor (placement.cpp), the load (load.cpp), the depth from below
// (rasterise.cpp), the elastic foundation (foundation.cpp), the sensor
// (sensor.cpp).
//
// Dimension legend: T frames, R x C mat cells, S x S samples per cell.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "ptnet/body.hpp"
#include "ptnet/sim.hpp"

namespace ptnet {

// simulate() with a given placement, read by the sensor model once per seed
// of `seeds` (options.seed is not used): result k is, bit for bit,
// simulate(motion, body, options with seed = seeds[k], placement), for the
// cost of one simulation plus the sensor model per seed.
std::vector<PressureSequence> simulate_reads(const Motion& motion, const Body& body, const SimOptions& options,
                                             const MotionPlacement& placement,
                                             const std::vector<std::uint64_t>& seeds,
                                             std::vector<FrameTrace>* trace = nullptr);

}  // namespace ptnet

namespace ptnet::detail {

// Some rigs put the toe joint well above the metatarsal heads, so a flat
// foot's ankle -> toe bone is flatter than the canonical 20.8 degrees and the
// sole would stand on its heel. Per foot (left, right): the canonical rest
// pitch minus the median of the bone's pitch over planted frames
// (ankle slower than 0.05 m/s), rad, bounded to +/- 0.5; 0 with < 5 planted frames.
std::array<double, 2> foot_pitch_offsets(const Motion& motion);
// The motion with its feet pitched by `offsets` (MotionPlacement::foot_pitch)
// when a foot's is more than ~2 degrees; unchanged otherwise (canonical motions).
Motion pitch_corrected(const Motion& motion, const std::array<double, 2>& offsets);

// The body (male, kFloorReferenceHeightCm, 65 kg) a motion's floor, feet
// and dynamics are found on.
const Body& reference_body();

// MotionDynamics::frozen_pelvis of a motion.
double frozen_pelvis_fraction(const Motion& motion);

// The lowest point (z, m) of a posed sole patch's surface, and of a posed
// foot's (the lower of its two patches): every cell of the sole's table
// (sole_lowest.cpp).
double patch_lowest_z(const SoleSurface& sole, const SolePatch& patch);
double foot_lowest_z(const SoleSurface& sole, const std::array<SolePatch, 2>& foot);
// Per row of a sole's table [nu]: its foot cells' columns and heights, so
// that the lowest point is found scanning only the rows that can hold it.
struct SoleRows {
  explicit SoleRows(const SoleSurface& sole);
  std::vector<int> first, last;  // [nu] the first and last column inside the foot (first > last: none)
  std::vector<double> h_lo, h_hi;  // [nu] the lowest and highest of the row's heights (m)
  std::vector<double> v_first, v_last;  // [nu] the sole coordinate v of the first and last column
  std::vector<double> u;                // [nu] the sole coordinate u of each row
  double h_abs = 0;                // the largest |height| of the table (m)
  double h_min = 0, h_max = 0;     // the lowest and highest height of the table (m; 0 when it has none)
};
// The same values as above, bit for bit, through `rows` (of `sole`).
double patch_lowest_z(const SoleSurface& sole, const SoleRows& rows, const SolePatch& patch);
double foot_lowest_z(const SoleSurface& sole, const SoleRows& rows, const std::array<SolePatch, 2>& foot);
// Whether foot_lowest_z(sole, foot) - floor < band, as that computes it,
// scanning only the rows that can decide it: a foot on the floor.
bool foot_below(const SoleSurface& sole, const SoleRows& rows, const std::array<SolePatch, 2>& foot, double floor,
                double band);
// Lowers each foot's ankle and toe joints by MotionPlacement::foot_lift [left, right] (m).
void lift_feet(Pose& pose, const std::array<double, 2>& lift);
// MotionPlacement::foot_lift of a motion (pitch corrected) on `body` over
// its floor ([T], or empty: z = 0).
std::array<double, 2> foot_lifts(const Motion& motion, const Body& body, const std::vector<double>& floor);

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
// `contact` ([T], or null): the frames with a body surface on the floor
// (floor_contact); the vertical acceleration is then filtered within each
// stretch of contact and of none separately.
ComTrack com_track(const Motion& motion, const Body& body, double com_filter_hz,
                   const std::vector<bool>* contact = nullptr);

// What touches the floor in each frame of `motion` (pitch corrected) as
// `place` lays it (support.cpp).
struct SupportFrame {
  std::array<bool, 2> foot_down{};             // [left, right] the sole within the band
  std::array<Eigen::Vector2d, 2> heel, tip;    // [left, right] the sole's ends (world x, y; m)
  Eigen::Vector2d seat = Eigen::Vector2d::Zero();  // under the hips (world x, y; m): where a seat carries
  bool seat_possible = false;                       // the hips low enough to sit (kSeatHipHeight)
  std::vector<Eigen::Vector2d> other;               // other surfaces on the floor (hands, knees: world x, y; m)
};
struct FloorSupport {
  std::vector<bool> contact;        // [T] some body surface (a sole, a segment that touches the ground) within the band
  std::vector<SupportFrame> frames;  // [T]
};
FloorSupport floor_support(const Motion& motion, const Body& body, const MotionPlacement& place, double band_m);

// The share of each frame's load the floor carries (0..1, [T]): 1 but where
// the zero-moment point stays more than 5 cm outside the feet on the floor
// for 0.3 s or longer, which only another support explains (a seat: the
// body does not fall). There the feet carry what balances the load's moment
// about a seat under the hips (the rest is the seat's, which no mat under
// the feet senses), and their own load's point moves onto their support
// (zmp is changed). Smoothed over 0.1 s.
std::vector<double> seat_share(const FloorSupport& support, std::vector<Eigen::Vector2d>& zmp, double foot_width_m,
                               double fps);
// MotionDynamics::carried: the fraction of frames whose seat_share is under 0.98.
double carried_fraction(const Motion& motion, const Body& body, const SimOptions& options, const FloorSupport& support);

// Rows [first, last] of a frame that may hold pressure; the others are 0
// (first > last: none).
struct RowSpan {
  int first = 0, last = -1;
};

// ---------------------------------------------------- depth from below
// rasterise.cpp: the lowest body surface over S x S samples per mat cell.

// The S x S sample grid over the mat: sample (i, j) has its centre at
// X = L/2 - (i + 0.5) ds, Y = W/2 - (j + 0.5) ds (mat coordinates, m; L x W
// the mat, ds = pitch / S); samples with i, j outside [0, R S) x [0, C S)
// lie off the mat.
struct SampleGrid {
  SampleGrid(const MatSpec& mat, int subsamples);
  MatSpec mat;
  int s;                     // S
  double ds, half_l, half_w;  // sample pitch, L/2, W/2 (m)
  int rows, cols;            // R S, C S
  double sample_x(int i) const { return half_l - (i + 0.5) * ds; }
  double sample_y(int j) const { return half_w - (j + 0.5) * ds; }
  double cell_x(int r) const { return mat.cell_x(r); }
  double cell_y(int c) const { return mat.cell_y(c); }
  bool on_mat(int i, int j) const { return i >= 0 && i < rows && j >= 0 && j < cols; }
};

// Which surface a sample's height belongs to (with a trace).
enum Owner : unsigned char { kNone = 0, kLeftSole = 1, kRightSole = 2, kOther = 3 };

// A sample off the mat, its lowest surface (Rasteriser keeps one per position).
struct OffSample {
  float z;   // height (m)
  int i, j;  // sample indices, outside [0, R S) x [0, C S)
};

// One frame's depth from below, the foundation's input: the lowest surface
// height per sample on the mat, and every record off it.
struct DepthMap {
  explicit DepthMap(const SampleGrid& grid);
  // Whether some sample on the mat was written.
  bool written() const { return row1 >= row0; }

  SampleGrid grid;
  std::vector<float> z;           // [R S, C S] lowest surface height (m), +inf: none
  int row0, row1;                 // the sample rows written (row0 > row1: none)
  std::vector<int> span0, span1;  // [R S] the columns [span0, span1] written in each sample row
  float zlo;                      // lowest recorded height, on or off the mat (m; +inf: none)
  std::vector<OffSample> off;     // the samples off the mat, one per position
  // With a trace (Rasteriser::rasterise(..., true)): the surface of each
  // sample (Owner) and its sole coordinate u (0 heel .. 1 toe tip).
  std::vector<unsigned char> owner;  // [R S, C S]
  std::vector<float> u;              // [R S, C S]
  std::vector<unsigned char> off_owner;  // [off]
  std::vector<float> off_u;              // [off]
};

// A sole patch's maps from a sample to its table cell and height, and one
// row of them (rasterise.cpp).
struct PatchMap;
struct PatchRow;

// Depth-from-below rasteriser over the sample grid of the mat. Reused across
// frames: no allocation after the first frames.
class Rasteriser {
 public:
  // Surfaces at or above reach_m (the compliance band plus the maximum sink)
  // can never touch: they are not recorded.
  Rasteriser(const MatSpec& mat, int subsamples, double reach_m);

  // Rasterises one posed body (mat coordinates) into depth(), replacing the
  // previous frame's: the lowest surface height per sample, on and off the
  // mat. With `trace`, also which surface (left sole, right sole, other) and
  // where along the sole each sample lies. Without it, a body that cannot
  // reach the mat leaves the map empty (its frame reads 0 whatever the load).
  void rasterise(const Body& body, const PosedBody& posed, bool trace);
  const DepthMap& depth() const { return d_; }

 private:
  void patch(const SoleSurface& sole, const SolePatch& p, Owner owner);
  // Samples [k0, k1] of sample row i, at j0 + k, of the patch row `row`,
  // one by one through record().
  void record_samples(const PatchMap& m, const PatchRow& row, int i, int j0, int k0, int k1, Owner owner);
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
    if (z < d_.zlo) d_.zlo = z;
    if (d_.grid.on_mat(i, j)) {
      const std::size_t k = std::size_t(i) * d_.grid.cols + j;
      if (z < d_.z[k]) {
        d_.z[k] = z;
        if (trace_) d_.owner[k] = owner, d_.u[k] = u;
      }
    } else {
      d_.off.push_back({z, i, j});
      if (trace_) d_.off_owner.push_back(owner), d_.off_u.push_back(u);
    }
  }
  // Empties the map (only the rows and columns written).
  void clear();
  // Leaves one record per position off the mat, the lowest.
  void keep_lowest_off_mat();

  float reach_;
  bool trace_ = false;
  std::vector<std::size_t> off_order_;  // keep_lowest_off_mat's scratch
  std::vector<OffSample> off_kept_;
  std::vector<unsigned char> off_kept_owner_;
  std::vector<float> off_kept_u_;
  DepthMap d_;
};

// ---------------------------------------------------- elastic foundation
// foundation.cpp: the body sunk into the mat until it carries its load.

// The elastic foundation (sole tissue and mat foam, linear stiffness) under
// a frame's depth map; reused across frames (its scratch is the grid's
// size). distribute() runs its steps in order:
//  1. sink_level: the level s where sum over samples of k max(0, s - z) dA
//     = F, at most max_sink above the lowest surface point;
//  2. penetrate: each cell's mean penetration max(0, s - z) over its
//     samples, and the moments of the contact (a sample off the mat is a
//     cell of its own);
//  3. tilt_towards: the weights 1 + g . (r - c) that move the centre of
//     pressure towards the target (the zero-moment point), at most 0.6
//     standard deviations of the contact from its centroid c;
//  4. scale_to_load: weighted penetrations scaled so that the pressures x
//     cell area sum to F over all contact, on and off the mat;
//  5. trace_feet: who carries what (per sole, heel, forefoot, centre of
//     pressure along the sole, area; other body parts).
class Foundation {
 public:
  Foundation(const SampleGrid& grid, double compliance_m, double max_sink_m);

  // Sinks the body of `depth` into the foundation until it carries load_n
  // (stiffness in Pa per m of penetration) and writes each cell's pressure
  // (kPa) into frame[R * C], which must be all zero on entry (only the cells
  // under the contact are written); all zero when no surface is within the
  // compliance band. The pressures times the cell area sum to load_n over
  // all contact, on and off the mat. Fills *trace if given (needs a depth
  // map rasterised with a trace).
  // With `target` (mat coordinates X, Y; m), the foundation tilts so that the
  // centre of pressure moves towards it (the penetration of each cell is
  // weighted by max(0, 1 + g . (r - c)), c the penetration centroid), at most
  // 0.6 standard deviations of the contact away from c (so that no contact
  // cell of a compact footprint is unloaded). Returns the rows it wrote.
  RowSpan distribute(const DepthMap& depth, double load_n, double stiffness_pa_per_m, const Eigen::Vector2d* target,
                     float* frame, FrameTrace* trace);

 private:
  // The penetration-weighted moments of the contact (cells on the mat at
  // their centres, samples off it at theirs; m, m^2, m^3).
  struct Moments {
    double m0 = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
    void add(double p, double x, double y) {
      m0 += p, mx += p * x, my += p * y, mxx += p * x * x, mxy += p * x * y, myy += p * y * y;
    }
  };
  // The tilt's weight of a point: max(0, 1 + g . (r - c)).
  struct Tilt {
    Eigen::Vector2d centroid, g;
    double weight(double x, double y) const {
      return std::max(0.0, 1.0 + g.x() * (x - centroid.x()) + g.y() * (y - centroid.y()));
    }
  };
  // Step 4's result: the sum of weighted penetrations (m) and kPa per m.
  struct Load {
    double total = 0, scale = 0;
  };

  double sink_level(const DepthMap& d, double load_n, double stiffness_pa_per_m) const;
  Moments penetrate(const DepthMap& d, float lv, RowSpan rows, float* frame);
  void penetrate_row(const DepthMap& d, float lv, int r, float* frame, Moments& m);
  Tilt tilt_towards(const Moments& m, const Eigen::Vector2d* target) const;
  Load scale_to_load(const DepthMap& d, float lv, const Tilt& tilt, RowSpan rows, double load_n, float* frame) const;
  void trace_feet(const DepthMap& d, double level, const Tilt& tilt, const Load& load, double load_n,
                  FrameTrace& trace) const;

  SampleGrid grid_;
  float band_, max_sink_;
  std::vector<unsigned char> hit_;  // [C S] penetrate's scratch
  std::vector<int> cell0_, cell1_;  // [R] the cells of each row penetrate may write (cell0 > cell1: none)
};

// Applies the sensor model to one frame in place: [R * C] kPa. `scratch` has
// R * C floats; `rng` is the frame's noise stream state; the rows outside
// `pressed` are 0 on entry (distribute's span; default: any row).
void apply_sensor(const SensorModel& sensor, const MatSpec& mat, float* frame, float* scratch,
                  std::uint64_t& rng, RowSpan pressed = {0, 1 << 30});

}  // namespace ptnet::detail
