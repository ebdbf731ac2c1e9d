// Procedural motions: determinism, walking gait (alternating contacts,
// cadence, planted stance feet, on the mat, the pelvis' rise and fall),
// every category grounded and plausible, squats lower the pelvis, and the BVH round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "data_test_util.hpp"
#include "motion/motion_internal.hpp"
#include "motion_gait_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"

namespace ptnet {
namespace {

using testing::foot_contacts;
using testing::lowest_sole_z;
using testing::sole_points;

Motion make(Category c, int performer, int take = 1, double seconds = 12) {
  GenerateOptions o;
  o.category = c;
  o.performer = performer;
  o.take = take;
  o.seconds = seconds;
  return generate_motion(o);
}

double max_abs_diff(const Motion& a, const Motion& b) {
  double d = 0;
  for (int f = 0; f < std::min(a.size(), b.size()); ++f)
    for (int j = 0; j < kJointCount; ++j) d = std::max(d, (a.frames[f][j] - b.frames[f][j]).cwiseAbs().maxCoeff());
  return d;
}

TEST(Category, NamesRoundTripAndBadNameIsAnError) {
  for (Category c : kCategories) EXPECT_EQ(parse_category(category_name(c)), c);
  try {
    parse_category("jogging");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "expected a category (walking, rom, freestyle, acting), found 'jogging'");
  }
}

TEST(Performer, HeightsAreHumanDeterministicAndVaried) {
  std::set<double> heights;
  for (int p = 1; p <= 10; ++p) {
    const double h = performer_height_cm(p);
    EXPECT_EQ(h, performer_height_cm(p));
    EXPECT_GE(h, 150);
    EXPECT_LE(h, 200);
    heights.insert(h);
    EXPECT_EQ(performer_sex(p), p % 2);
  }
  EXPECT_GE(heights.size(), 8u);
  EXPECT_NE(performer_height_cm(1, 0), performer_height_cm(1, 7));
}

TEST(Generate, SameOptionsSameMotionOtherTakeOrPerformerDiffers) {
  for (Category c : kCategories) {
    const Motion a = make(c, 2, 1, 6), b = make(c, 2, 1, 6);
    ASSERT_EQ(a.size(), 180);
    EXPECT_EQ(max_abs_diff(a, b), 0.0) << category_name(c);
    EXPECT_GT(max_abs_diff(a, make(c, 2, 2, 6)), 0.05) << category_name(c);
    EXPECT_GT(max_abs_diff(a, make(c, 3, 1, 6)), 0.05) << category_name(c);
  }
}

TEST(Generate, BonesHaveTheCanonicalLengthsOfThePerformer) {
  const Motion m = make(Category::freestyle, 4, 1, 4);
  const Pose o = canonical_rest_offsets(performer_height_cm(4));
  for (const Pose& p : m.frames)
    for (int j = 1; j < kJointCount; ++j)
      ASSERT_NEAR((p[j] - p[joint_parent(j)]).norm(), o[j].norm(), 1e-9) << joint_name(j);
}

TEST(Generate, RejectsBadOptions) {
  GenerateOptions o;
  o.seconds = 0;
  EXPECT_THROW(generate_motion(o), Error);
  o.seconds = 5;
  o.performer = 0;
  EXPECT_THROW(generate_motion(o), Error);
  o.performer = 1;
  o.fps = 0;
  EXPECT_THROW(generate_motion(o), Error);
  o.fps = 30;
  // height_cm 0 is the performer's own; anything else outside [50, 250] was
  // once taken for 0 (issue 24, probe defect 11).
  for (const double h : {-5.0, 20.0, 300.0, std::nan("")}) {
    o.height_cm = h;
    EXPECT_EQ(testing_util::error_of([&] { generate_motion(o); }),
              "generate_motion: height_cm: expected 0 (the performer's own) or a height in [50, 250] cm, found " +
                  number_text(h));
  }
}

// Walking: contacts alternate left/right at 1.6-2.0 steps/s; a stance foot
// neither slides (< 2 cm) nor floats or sinks (> 2 cm); heel strikes first
// and the toes leave last; it stays on the 1.6 m x 0.56 m mat.
TEST(Walking, AlternatingPlantedStepsAtARealisticCadenceOnTheMat) {
  for (int performer = 1; performer <= 4; ++performer) {
    SCOPED_TRACE("performer " + std::to_string(performer));
    const Motion m = make(Category::walking, performer, 1, 15);
    const auto contacts = foot_contacts(m);
    ASSERT_GE(contacts.size(), 20u);
    // Alternation (the first contacts are the standing start).
    for (std::size_t i = 3; i < contacts.size(); ++i) EXPECT_NE(contacts[i].side, contacts[i - 1].side) << i;
    const double seconds = (contacts.back().first - contacts[2].first) / m.fps;
    const double cadence = (contacts.size() - 3) / seconds;
    EXPECT_GE(cadence, 1.6);
    EXPECT_LE(cadence, 2.0);
    for (const auto& c : contacts) {
      EXPECT_LT(c.heel_slip, 0.02) << c.first;
      EXPECT_LT(c.tip_slip, 0.02) << c.first;
      EXPECT_GT(c.min_z, -0.02);
      EXPECT_LT(c.min_z, 0.005);  // really on the ground at some point
    }
    // Heel strike: at the start of a contact the heel is lower than the toe
    // tip; at its end (toe-off) the toe tip is lower than the heel.
    int heel_first = 0, toe_last = 0, n = 0;
    for (std::size_t i = 3; i + 1 < contacts.size(); ++i) {
      const auto& c = contacts[i];
      const auto a = sole_points(m.frames[c.first], c.side), b = sole_points(m.frames[c.last], c.side);
      heel_first += a.heel.z() < a.tip.z();
      toe_last += b.tip.z() < b.heel.z();
      ++n;
    }
    EXPECT_GE(heel_first, 0.7 * n);
    EXPECT_GE(toe_last, 0.9 * n);
    double xmin = 1e9, xmax = -1e9;
    for (const Pose& p : m.frames) {
      EXPECT_GT(lowest_sole_z(p), -0.02);
      for (int s = 0; s < 2; ++s) {
        const auto sp = sole_points(p, s);
        for (const auto& q : {sp.heel, sp.tip}) {
          EXPECT_LE(std::abs(q.x()), 0.8);
          EXPECT_LE(std::abs(q.y()), 0.28);
        }
      }
      xmin = std::min(xmin, p[kPelvis].x());
      xmax = std::max(xmax, p[kPelvis].x());
    }
    EXPECT_LE(xmax - xmin, 1.4);
    EXPECT_GE(xmax - xmin, 0.8);  // it really walks
  }
}

TEST(Walking, ArmsSwingOppositeToTheLegs) {
  const Motion m = make(Category::walking, 1, 1, 10);
  // Forward offset of the left wrist vs the right, against the left ankle vs
  // the right, in the pelvis' heading: negatively correlated.
  double sxy = 0, sxx = 0, syy = 0;
  for (const Pose& p : m.frames) {
    Eigen::Vector3d fwd = (p[kLeftHip] - p[kRightHip]).cross(Eigen::Vector3d::UnitZ()).normalized();
    fwd = -fwd;  // left x up = backward
    const double legs = fwd.dot(p[kLeftAnkle] - p[kRightAnkle]);
    const double arms = fwd.dot(p[kLeftWrist] - p[kRightWrist]);
    sxy += legs * arms;
    sxx += legs * legs;
    syy += arms * arms;
  }
  EXPECT_LT(sxy / std::sqrt(sxx * syy), -0.5);
}

// The pelvis rides the stance legs (the rise and fall that gives walking its
// double-humped load): lower in double support than in single stance, a
// peak-to-peak of a few centimetres per step (a real treadmill walk: 4.1 cm),
// and never held at one height while the feet step, so the simulator's
// dynamics check has nothing to say about it.
TEST(Walking, PelvisRisesInSingleStanceAndSinksInDoubleSupport) {
  for (int performer = 1; performer <= 4; ++performer) {
    SCOPED_TRACE("performer " + std::to_string(performer));
    const Motion m = make(Category::walking, performer, 1, 15);
    const auto frame = [&](int f) -> const Pose& { return m.frames[std::size_t(f)]; };
    // Frames of straight walking (the pelvis moving on at > 0.6 m/s: not
    // turning at the mat's ends nor standing) and how many feet are down.
    std::vector<int> feet_down(std::size_t(m.size()), 0);
    for (const auto& c : foot_contacts(m))
      for (int f = c.first; f <= c.last; ++f) ++feet_down[std::size_t(f)];
    std::vector<bool> walking(std::size_t(m.size()), false);
    for (int f = 1; f + 1 < m.size(); ++f)
      walking[std::size_t(f)] = (frame(f + 1)[kPelvis] - frame(f - 1)[kPelvis]).head<2>().norm() * m.fps / 2 > 0.6;
    double single = 0, both = 0;
    int n_single = 0, n_both = 0;
    for (int f = 0; f < m.size(); ++f) {
      if (!walking[std::size_t(f)]) continue;
      const double z = frame(f)[kPelvis].z();
      if (feet_down[std::size_t(f)] == 1) single += z, ++n_single;
      if (feet_down[std::size_t(f)] == 2) both += z, ++n_both;
    }
    ASSERT_GT(n_single, 0);
    ASSERT_GT(n_both, 0);
    const double rise = single / n_single - both / n_both;
    // Peak-to-peak over each step (0.55 s) of straight walking.
    const int step = int(std::lround(0.55 * m.fps));
    std::vector<double> swings;
    for (int f = 0; f + step <= m.size(); f += step) {
      double lo = 1e9, hi = -1e9;
      bool straight = true;
      for (int g = f; g < f + step; ++g) {
        straight = straight && walking[std::size_t(g)];
        lo = std::min(lo, frame(g)[kPelvis].z());
        hi = std::max(hi, frame(g)[kPelvis].z());
      }
      if (straight) swings.push_back(hi - lo);
    }
    ASSERT_FALSE(swings.empty());
    std::nth_element(swings.begin(), swings.begin() + swings.size() / 2, swings.end());
    const double median = swings[swings.size() / 2];
    std::printf("performer %d: single - double support %.4f m, peak-to-peak %.4f m (%zu steps)\n", performer, rise,
                median, swings.size());
    EXPECT_GT(rise, 0.005);
    EXPECT_GT(median, 0.015);
    EXPECT_LT(median, 0.07);
    EXPECT_EQ(check_dynamics(m, SimOptions{}).frozen_pelvis, 0.0);
  }
}

// Every category: finite, grounded (lowest sole point within 2 cm of the
// floor in nearly every frame), joint speeds bounded, pelvis height human,
// mostly in place for the non-walking categories.
TEST(Generate, EveryCategoryIsGroundedAndPlausible) {
  for (Category c : kCategories)
    for (int performer = 1; performer <= 3; ++performer) {
      SCOPED_TRACE(std::string(category_name(c)) + " performer " + std::to_string(performer));
      const Motion m = make(c, performer, performer, 15);
      const double h = performer_height_cm(performer) / 100;
      int grounded = 0;
      double vmax = 0, zmin = 1e9, zmax = -1e9, rmax = 0;
      for (int f = 0; f < m.size(); ++f) {
        const Pose& p = m.frames[f];
        for (const auto& v : p) ASSERT_TRUE(v.allFinite());
        const double low = lowest_sole_z(p);
        EXPECT_GT(low, -0.02);
        // Whatever touches the floor is on the 1.6 m x 0.56 m mat.
        for (int s = 0; s < 2; ++s) {
          const auto sp = sole_points(p, s);
          for (const auto& q : {sp.heel, sp.tip})
            if (q.z() < 0.02) EXPECT_TRUE(std::abs(q.x()) <= 0.8 && std::abs(q.y()) <= 0.28) << f;
        }
        grounded += low < 0.02;
        if (f > 0)
          for (int j = 0; j < kJointCount; ++j) vmax = std::max(vmax, (p[j] - m.frames[f - 1][j]).norm() * m.fps);
        zmin = std::min(zmin, p[kPelvis].z());
        zmax = std::max(zmax, p[kPelvis].z());
        rmax = std::max(rmax, p[kPelvis].head<2>().norm());
      }
      EXPECT_GE(grounded, m.size() - 1);
      EXPECT_LT(vmax, 7.0);           // m/s: fastest joint (swing foot, wrist)
      EXPECT_GT(zmin, 0.25 * h);      // deepest squat
      EXPECT_LT(zmax, 0.62 * h);      // standing on the toes
      if (c != Category::walking) EXPECT_LT(rmax, 1.0);
      if (c != Category::walking) {
        // Stance feet do not slide.
        for (const auto& k : foot_contacts(m)) {
          EXPECT_LT(k.heel_slip, 0.02) << k.first;
          EXPECT_LT(k.tip_slip, 0.02) << k.first;
        }
      }
    }
}

TEST(Rom, SquatsLowerThePelvis) {
  // Some take of some performer squats; the pelvis then drops by > 0.12 H
  // below standing with both feet flat on the floor.
  bool found = false;
  for (int take = 1; take <= 4 && !found; ++take) {
    const Motion m = make(Category::rom, 1, take, 20);
    const double h = performer_height_cm(1) / 100;
    for (const Pose& p : m.frames) {
      const bool flat = std::abs(sole_points(p, 0).heel.z()) < 0.01 && std::abs(sole_points(p, 1).heel.z()) < 0.01 &&
                        std::abs(sole_points(p, 0).tip.z()) < 0.01 && std::abs(sole_points(p, 1).tip.z()) < 0.01;
      if (flat && p[kPelvis].z() < (0.53 - 0.12) * h) found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(MotionToBvh, ReadingItBackGivesTheSamePositions) {
  for (Category c : kCategories) {
    SCOPED_TRACE(category_name(c));
    const Motion m = make(c, 3, 1, 4);
    const Bvh bvh = motion_to_bvh(m);
    ASSERT_EQ(bvh.frames(), m.size());
    EXPECT_EQ(bvh.joints[0].name, "pelvis");
    EXPECT_EQ(bvh.joints[0].channels.size(), 6u);
    EXPECT_EQ(bvh.joints[0].channels[3], Channel::Zrotation);
    const Bvh back = parse_bvh(format_bvh(bvh), "roundtrip.bvh");
    const auto world = forward_kinematics(back, 0.01, UpAxis::y);
    const int nj = int(back.joints.size());
    ASSERT_EQ(nj, kJointCount);
    double err = 0;
    for (int f = 0; f < m.size(); ++f)
      for (int j = 0; j < kJointCount; ++j) {
        const int b = back.find(joint_name(j));
        ASSERT_GE(b, 0);
        err = std::max(err, (world[std::size_t(f) * nj + b] - m.frames[f][j]).norm());
      }
    EXPECT_LT(err, 1e-4);
    // And the whole loader maps it and finds the performer's height.
    MotionOptions opt;
    opt.fps = 0;
    const Motion loaded = motion_from_bvh(back, opt);
    EXPECT_NEAR(standing_height(loaded), standing_height(m), 1e-3);
    // (a relaxed stance: knees soft, trunk and head a little forward)
    EXPECT_NEAR(standing_height(m), performer_height_cm(3) / 100, 0.05 * performer_height_cm(3) / 100);
  }
}

}  // namespace
}  // namespace ptnet
