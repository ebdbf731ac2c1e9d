// Canonical joints and the mapping from common BVH naming schemes.
//
// Names are compared case-insensitively after dropping namespace prefixes
// (`mixamorig:`, anything up to the last ':' or '|'), known rig prefixes
// (`CC_Base_`, `Character1_`, `Bip01_` ...) and separators, so `L_Hip`,
// `l_hip` and `LHip` are the same name. Each canonical joint has a list of
// candidate names tried in order; a candidate must descend from the joint
// already chosen for its canonical parent, which separates e.g. SMPL's
// L_Foot (a toe joint, below L_Ankle) from Character Creator's L_Foot (the
// ankle). Spine and chest are chosen on the pelvis -> neck chain by bone
// length along it (canonical skeleton: spine 0.070 H and chest 0.190 H above
// the pelvis, of 0.288 H to the neck, docs/anthropometry.md), which
// fits CMU (Spine, Spine1), Mixamo (Spine, Spine2), SMPL (Spine1, Spine3)
// and Character Creator (Spine01, Spine02) alike.
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "motion/motion_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

constexpr std::array<const char*, kJointCount> kNames = {
    "pelvis",     "spine",          "chest",       "neck",          "head",
    "left_hip",   "left_knee",      "left_ankle",  "left_toe",      "right_hip",
    "right_knee", "right_ankle",    "right_toe",   "left_shoulder", "left_elbow",
    "left_wrist", "right_shoulder", "right_elbow", "right_wrist"};

constexpr std::array<int, kJointCount> kParents = {
    -1,         kPelvis,    kSpine,         kChest,     kNeck,
    kPelvis,    kLeftHip,   kLeftKnee,      kLeftAnkle, kPelvis,
    kRightHip,  kRightKnee, kRightAnkle,    kChest,     kLeftShoulder,
    kLeftElbow, kChest,     kRightShoulder, kRightElbow};

// Fractions of the pelvis -> neck chain length (0.070 / 0.288, 0.190 / 0.288).
constexpr double kSpineFraction = 0.070 / 0.288;
constexpr double kChestFraction = 0.190 / 0.288;

std::string normalise(const std::string& name) {
  std::string s = name;
  const std::size_t cut = s.find_last_of(":|");
  if (cut != std::string::npos) s = s.substr(cut + 1);
  std::string low = lower(s);
  static const char* const kPrefixes[] = {"cc_base_", "mixamorig_", "mixamorig",
                                          "bip001_",  "bip01_",     "bip001 ",
                                          "bip01 ",   "def-",       "def_"};
  for (const char* p : kPrefixes) {
    const std::string pre(p);
    if (low.size() > pre.size() && low.compare(0, pre.size(), pre) == 0) {
      low = low.substr(pre.size());
      break;
    }
  }
  // "character1_", "character_" (MotionBuilder HumanIK).
  if (low.compare(0, 9, "character") == 0) {
    std::size_t i = 9;
    while (i < low.size() && std::isdigit(static_cast<unsigned char>(low[i]))) ++i;
    if (i < low.size() && low[i] == '_' && i + 1 < low.size()) low = low.substr(i + 1);
  }
  std::string out;
  for (char c : low)
    if (std::isalnum(static_cast<unsigned char>(c))) out += c;
  return out;
}

// Candidate names (normalised) for one side, written for the left; the
// right side replaces "left" by "right" and a leading "l" by "r".
struct SideNames {
  int joint;
  std::vector<std::string> names;
};

const std::vector<SideNames>& limb_names() {
  static const std::vector<SideNames> kLimbs = {
      {kLeftHip, {"leftupleg", "lupleg", "lthigh", "leftthigh", "lhip", "lefthip", "lfemur"}},
      {kLeftKnee,
       {"leftleg", "lleg", "lcalf", "leftcalf", "lknee", "leftknee", "leftlowleg", "lshin",
        "leftshin", "ltibia"}},
      {kLeftAnkle, {"lankle", "leftankle", "leftfoot", "lfoot"}},
      {kLeftToe,
       {"lefttoebase", "ltoebase", "lefttoe", "ltoe", "lefttoes", "ltoes", "lball", "leftball",
        "lfoot", "leftfoot"}},
      {kLeftShoulder,
       {"leftarm", "lupperarm", "leftupperarm", "larm", "lhumerus", "lshoulder", "leftshoulder"}},
      {kLeftElbow,
       {"leftforearm", "lforearm", "lelbow", "leftelbow", "llowerarm", "leftlowerarm", "lradius"}},
      {kLeftWrist, {"lwrist", "leftwrist", "lefthand", "lhand"}},
  };
  return kLimbs;
}

std::string to_right(const std::string& left) {
  if (left.compare(0, 4, "left") == 0) return "right" + left.substr(4);
  return "r" + left.substr(1);
}

int mirror(int joint) {
  if (joint >= kLeftHip && joint <= kLeftToe) return joint + 4;
  if (joint >= kLeftShoulder && joint <= kLeftWrist) return joint + 3;
  return joint;
}

bool descends(const Bvh& bvh, int j, int ancestor) {
  if (ancestor < 0) return true;
  for (int p = bvh.joints[std::size_t(j)].parent; p >= 0; p = bvh.joints[std::size_t(p)].parent)
    if (p == ancestor) return true;
  return false;
}

// First joint whose normalised name is in `names` (in list order) and that
// descends from `ancestor`; zero-length joints (offset 0, as CMU's Neck) are
// passed over when a later candidate also fits.
int pick(const Bvh& bvh, const std::vector<std::string>& norm,
         const std::vector<std::string>& names, int ancestor) {
  int zero_length = -1;
  for (const std::string& want : names)
    for (std::size_t j = 0; j < norm.size(); ++j)
      if (norm[j] == want && descends(bvh, int(j), ancestor)) {
        if (bvh.joints[j].offset.norm() > 1e-9 || bvh.joints[j].parent < 0) return int(j);
        if (zero_length < 0) zero_length = int(j);
      }
  return zero_length;
}

}  // namespace

const char* joint_name(int joint) {
  if (joint < 0 || joint >= kJointCount) return "?";
  return kNames[std::size_t(joint)];
}

int joint_parent(int joint) {
  if (joint < 0 || joint >= kJointCount) return -1;
  return kParents[std::size_t(joint)];
}

namespace {

using JointMap = std::array<int, kJointCount>;

// Our own canonical names (motion_to_bvh writes them), taken as they are:
// true when every joint has one.
bool map_own_names(const std::vector<std::string>& norm, JointMap& map) {
  map.fill(-1);
  for (int k = 0; k < kJointCount; ++k) {
    const std::string want = normalise(kNames[std::size_t(k)]);
    for (std::size_t j = 0; j < norm.size() && map[std::size_t(k)] < 0; ++j)
      if (norm[j] == want) map[std::size_t(k)] = int(j);
    if (map[std::size_t(k)] < 0) return false;
  }
  return true;
}

// Pelvis, neck, head and the limbs of both sides, by name.
void map_named(const Bvh& bvh, const std::vector<std::string>& norm, JointMap& map) {
  map[kPelvis] = pick(bvh, norm, {"hips", "hip", "pelvis", "root"}, -1);
  if (map[kPelvis] < 0) return;
  map[kNeck] = pick(bvh, norm, {"neck", "necktwist01", "neck01", "neck1", "lowerneck"}, map[kPelvis]);
  if (map[kNeck] >= 0) map[kHead] = pick(bvh, norm, {"head"}, map[kNeck]);
  for (const SideNames& limb : limb_names()) {
    std::vector<std::string> right;
    for (const std::string& n : limb.names) right.push_back(to_right(n));
    for (int side = 0; side < 2; ++side) {
      const int joint = side == 0 ? limb.joint : mirror(limb.joint);
      const int parent = joint_parent(joint);
      // Arms hang from the chest, chosen below: any joint under the pelvis.
      const int ancestor = (joint == kLeftShoulder || joint == kRightShoulder) ? map[kPelvis] : map[parent];
      if (ancestor < 0) continue;
      map[joint] = pick(bvh, norm, side == 0 ? limb.names : right, ancestor);
    }
  }
}

// Spine and chest: on the chain strictly between pelvis and neck, nearest
// the anthropometric fractions of its length; shoulders must hang from them.
void map_spine(const Bvh& bvh, JointMap& map) {
  if (map[kPelvis] < 0 || map[kNeck] < 0) return;
  std::vector<int> chain;  // neck's ancestors up to (not incl.) the pelvis, top-down
  for (int p = bvh.joints[std::size_t(map[kNeck])].parent; p >= 0 && p != map[kPelvis];
       p = bvh.joints[std::size_t(p)].parent)
    chain.insert(chain.begin(), p);
  std::vector<double> along(chain.size());
  double length = 0;
  for (std::size_t i = 0; i < chain.size(); ++i) {
    length += bvh.joints[std::size_t(chain[i])].offset.norm();
    along[i] = length;
  }
  length += bvh.joints[std::size_t(map[kNeck])].offset.norm();
  if (chain.size() == 1) {
    map[kSpine] = map[kChest] = chain[0];
  } else if (chain.size() >= 2 && length > 0) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < chain.size(); ++a)
      for (std::size_t b = a + 1; b < chain.size(); ++b) {
        const double cost =
            std::abs(along[a] / length - kSpineFraction) + std::abs(along[b] / length - kChestFraction);
        if (cost < best - 1e-12) {
          best = cost;
          map[kSpine] = chain[a];
          map[kChest] = chain[b];
        }
      }
  }
  for (int joint : {kLeftShoulder, kRightShoulder})
    if (map[joint] >= 0 && map[kChest] >= 0 && !descends(bvh, map[joint], map[kChest]) &&
        !descends(bvh, map[joint], map[kSpine]))
      map[joint] = -1;
}

// Throws Error naming the joints not mapped and the joints found.
void check_complete(const Bvh& bvh, const JointMap& map) {
  std::string missing;
  for (int k = 0; k < kJointCount; ++k)
    if (map[std::size_t(k)] < 0) missing += (missing.empty() ? "" : ", ") + std::string(kNames[std::size_t(k)]);
  if (missing.empty()) return;
  std::string found;
  for (const BvhJoint& j : bvh.joints) found += (found.empty() ? "" : " ") + j.name;
  throw Error::in(bvh.source.empty() ? "BVH" : bvh.source,
                  "cannot map to the canonical joints: missing " + missing + "; joints found: " + found);
}

}  // namespace

std::array<int, kJointCount> map_canonical(const Bvh& bvh) {
  std::vector<std::string> norm;
  for (const BvhJoint& j : bvh.joints) norm.push_back(normalise(j.name));
  JointMap map;
  if (map_own_names(norm, map)) return map;
  map.fill(-1);
  map_named(bvh, norm, map);
  map_spine(bvh, map);
  check_complete(bvh, map);
  return map;
}

}  // namespace ptnet
