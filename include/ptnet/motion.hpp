// ptnet/motion.hpp: motion capture in and out (BVH), forward kinematics,
// canonical joints, resampling, retargeting and procedural motions.
//
//   ptnet::MotionOptions opt;                 // units auto, BVH y-up, 30 Hz
//   ptnet::Motion m = ptnet::load_motion("walk.bvh", opt);
//   ptnet::Motion r = ptnet::retarget(m, 182.0);   // onto a 182 cm body
//   ptnet::write_bvh(ptnet::motion_to_bvh(r), "walk_182.bvh", /*force=*/false);
//
// World frame (every Motion): metres, right-handed, z up, ground z = 0. For
// the canonical skeleton +x is the rest-pose facing direction and +y the
// body's left. A y-up BVH maps to it by (x, y, z)_bvh -> (z, x, y)_world.
//
// Dimension legend: F frames, J joints of a BVH rig, K = kJointCount
// canonical joints.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/paper.hpp"

namespace ptnet {

// ---------------------------------------------------------------- BVH files

enum class Channel : std::uint8_t { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

struct BvhJoint {
  std::string name;
  int parent = -1;                          // index into Bvh::joints, -1 for ROOT
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // file units, file axes
  std::vector<Channel> channels;            // 0, 3 or 6, in file order
  int first_channel = 0;                    // column of channels[0] in a frame
  bool has_end_site = false;
  Eigen::Vector3d end_site = Eigen::Vector3d::Zero();
};

struct Bvh {
  std::vector<BvhJoint> joints;  // parents before children (file order)
  int channel_count = 0;
  double frame_time = 1.0 / 30;  // s
  std::vector<double> values;    // [F, channel_count], file units, degrees
  std::string source;            // file name, for error messages

  int frames() const { return channel_count ? int(values.size() / channel_count) : 0; }
  double fps() const { return 1.0 / frame_time; }
  const double* frame(int f) const { return values.data() + std::size_t(f) * channel_count; }
  int find(std::string_view joint_name) const;  // -1 if absent
};

// Reads a BVH file. Errors are one line, naming the file:
// "walk.bvh:42: expected CHANNELS, found OFFSET".
Bvh read_bvh(const std::string& path);
// Atomic write (temporary file + rename); refuses to overwrite unless force,
// and a name that says another format (check_bvh_output).
void write_bvh(const Bvh& bvh, const std::string& path, bool force);
// What write_bvh checks of `path`, for before the work: a .bvh name (any
// case; Error "w.trc: expected a .bvh file name (BVH is written), found
// '.trc'": check_output_name) and check_output_path (ptnet/io.hpp).
void check_bvh_output(const std::string& path, bool force);

// ------------------------------------------------------- units and up axis

// cmu: the CMU "cgspeed" BVH unit, 1/0.45 inch = 0.05644 m.
enum class Units { automatic, m, cm, mm, in, cmu };
enum class UpAxis { y, z };
Units parse_units(const std::string& text);  // "auto|m|cm|mm|in|cmu"
UpAxis parse_up_axis(const std::string& text);  // "y|z"
const char* up_axis_name(UpAxis up);            // "y", "z"
const char* units_name(Units units);

// Metres per file unit. For Units::automatic, chosen from the rest-pose
// standing height so that it falls in a human range.
double metres_per_unit(const Bvh& bvh, Units units, UpAxis up);

// -------------------------------------------------------- canonical joints

enum Joint : int {
  kPelvis, kSpine, kChest, kNeck, kHead,
  kLeftHip, kLeftKnee, kLeftAnkle, kLeftToe,
  kRightHip, kRightKnee, kRightAnkle, kRightToe,
  kLeftShoulder, kLeftElbow, kLeftWrist,
  kRightShoulder, kRightElbow, kRightWrist,
  kJointCount
};
const char* joint_name(int joint);             // "pelvis", "left_hip", ...

// Index of the BVH joint for each canonical joint. Recognises CMU, Character
// Creator (CC_Base_*), Mixamo (mixamorig:*), SMPL (L_Hip ...), Vicon /
// TotalCapture naming. Throws Error listing the names found if it cannot.
std::array<int, kJointCount> map_canonical(const Bvh& bvh);

// ------------------------------------------------------------------ motion

using Pose = std::array<Eigen::Vector3d, kJointCount>;  // world positions, m

struct Motion {
  std::string name;
  double fps = kFps;
  std::vector<Pose> frames;  // [F]
  double start_s = 0;        // time of frame 0 on the recording's clock (s): a .trc's first Time
  // [F] or empty: the height retarget() added to each frame to keep its
  // supporting foot on the floor (m). A correction of the copy's geometry,
  // not a motion of the body: the simulator's load leaves it out.
  std::vector<double> support_shift_m;
  int size() const { return int(frames.size()); }
};

// The frame rates a dataset and a generated motion play at (a motion is
// read at up to kReadFpsRange, below).
inline constexpr Range kFpsRange{1, 1000};

struct MotionOptions {
  Units units = Units::automatic;
  double metres_per_unit = 0;  // > 0 overrides `units` (e.g. from clips.csv)
  UpAxis up = UpAxis::y;
  bool keep_tpose = false;     // a leading T-pose frame is dropped by default
  // Resample to this rate (in kReadFpsRange); <= 0 keeps the file's. A file
  // whose own rate is within 1e-4 of it is read as recorded at it, frame for
  // frame: its Frame Time is that rate written with a few digits (0.033333
  // s is 30.0003 fps, 0.016667 s 59.9988, .0083333 s 120.0005).
  double fps = kFps;
  // A treadmill's belt is detected (the lower foot sliding backwards at over
  // 0.3 m/s while the pelvis stays) and removed, so that a treadmill trial
  // is simulated as the same gait overground.
  bool remove_belt = true;
  // Marker files (.trc, ptnet/markers.hpp): a shipped map's name or a map
  // file ("": the shipped map that places the file), a static trial that
  // calibrates the joint centres its markers miss ("": none), and the
  // longest gap of a marker filled by interpolation (s).
  std::string marker_map;
  std::string static_markers;
  double max_gap_s = 0.1;
};
// The rates a motion is read at: a dataset's fps (kFpsRange) over a clip's
// playback speed (kClipSpeedRange, simulate_dataset.hpp), up to 1000 / 0.25.
inline constexpr Range kReadFpsRange{0, 4000, true};

// True if frame `f` is a T-pose: arms out horizontally, legs straight.
bool is_tpose(const Bvh& bvh, int frame, const std::array<int, kJointCount>& map, double scale,
              UpAxis up);

// Reads, maps, drops a leading T-pose, resamples, and runs FK; then grounds:
// shifts z so that the floor (lower quartile over frames of the lowest foot
// point: heel or toe tip) is at z = 0. Name: the file stem. Throws Error for
// an options.fps that is neither a finite number <= 0 nor in kReadFpsRange
// (NaN, infinity).
Motion motion_from_bvh(const Bvh& bvh, const MotionOptions& options);
// A BVH file, or a marker file for a path ending in .trc (motion_from_trc).
Motion load_motion(const std::string& path, const MotionOptions& options);

// The motion as if overground: every joint moved by -velocity * t (t from
// its first frame; velocity in world x, y, m/s): a treadmill trial's lab
// positions (read without remove_belt) with the belt its MarkerReport finds
// (belt_velocity_mps) taken out, as remove_belt does.
Motion without_belt(Motion motion, const Eigen::Vector2d& velocity);

// Standing height (m) of the first frames: top of head (head joint plus head
// length) above the lowest foot point.
double standing_height(const Motion& motion);

// -------------------------------------------------------- canonical skeleton

// Retargets onto a body of `height_cm`: every bone keeps its world direction
// per frame (joint rotations kept, up to bone twist) and takes the target's
// length; the pelvis (spine, hips) and chest (neck, shoulders) groups are
// placed rigidly by the frame of their source bones; the root's horizontal
// displacement from frame 0 and its height scale with leg length; each frame
// is then raised or lowered so that the supporting ankle stands where the
// scaled source's does (legs of other proportions than the source's reach
// elsewhere as the knees bend; Motion::support_shift_m records it); the
// motion is re-grounded so that the lowest foot point during stance (5th
// percentile over frames of the lowest heel or toe tip) is at z = 0. Throws
// Error for an empty motion or a height outside 50-250 cm.
Motion retarget(const Motion& motion, double height_cm);

// The factor retarget(motion, height_cm) scales the root's horizontal path by
// (about frame 0's pelvis): the canonical leg length of height_cm over the
// motion's mean leg length (hip -> knee -> ankle). Throws Error as retarget.
double retarget_scale(const Motion& motion, double height_cm);

// The motion as a BVH on the canonical skeleton (joints named as
// joint_name(), y-up, centimetres, root Xposition Yposition Zposition then
// ZXY rotation channels; End Sites: head top, toe tips, hands). Rotations
// come from the positions (pelvis and chest: frame of their lateral and up
// bones; others: swing in the parent's frame). For canonical-proportioned
// motions (generate_motion, retarget) reading it back gives the same world
// positions within 1e-4 m.
Bvh motion_to_bvh(const Motion& motion);

// The pitch (rad, ~0.36) below the horizontal of the canonical ankle -> toe
// joint bone of a foot standing flat: the ankle 0.039 H and the toe joint
// 0.009 H above the sole, 0.079 H apart.
double rest_foot_pitch();
// Rotates each foot's toe joint about its ankle, toe down by
// offsets[side] (rad; [left, right]; about the horizontal axis normal to the bone).
void pitch_feet(Pose& pose, const std::array<double, 2>& offsets);
// The back of the heel and the toe tip (world, m) of the left (side 0) or
// right (side 1) foot: the canonical foot scaled to its ankle -> toe bone.
std::array<Eigen::Vector3d, 2> foot_ends(const Pose& pose, int side);

// ------------------------------------------------------ procedural motions

enum class Category { walking, rom, freestyle, acting };
inline constexpr std::array<Category, 4> kCategories{Category::walking, Category::rom,
                                                     Category::freestyle, Category::acting};
Category parse_category(const std::string& text);  // throws Error
const char* category_name(Category category);
// The motion id of a performer's take of a category: "p3_walking_t2" (the
// procedural motions, their BVH files and the datasets' motion_id).
std::string motion_id(int performer, Category category, int take);

struct GenerateOptions {
  Category category = Category::walking;
  int performer = 1;      // 1.. : per-performer style (seeded by this)
  int take = 1;           // 1.. : per-take variation
  double seconds = 10;
  double fps = kFps;
  double height_cm = 0;   // 0: the performer's own height
  std::uint64_t seed = 0; // mixed with performer and take
};

// A seeded procedural clip on the canonical skeleton, grounded, with planted
// stance feet. Same options, same motion. Walking paces back and forth along
// x on the 1.6 m x 0.56 m mat (turning at its ends); the other categories stay
// near the origin. Throws Error for seconds outside (0, 3600], fps outside
// [1, 1000], performer or take < 1.
Motion generate_motion(const GenerateOptions& options);

// Height (cm) of a procedural performer (deterministic in `performer`; the
// sexes alternate, each performer drawn from its sex's stature).
double performer_height_cm(int performer, std::uint64_t seed = 0);

}  // namespace ptnet
