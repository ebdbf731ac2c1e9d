// The lowest point of a posed sole (src/sim/sole_lowest.cpp): the pruned
// scan through SoleRows returns the reference's value bit for bit (the
// feet's lifts come from it), and foot_below decides as the reference's
// value does whether a foot is within the band over the floor
// for feet in every orientation, on short, tall, light and heavy bodies,
// in the frames of a walk, with ties (a level sole), and with coordinates
// that are not finite.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "ptnet/body.hpp"
#include "ptnet/motion.hpp"
#include "sim/sim_internal.hpp"
#include "sim_poses.hpp"

namespace ptnet {
namespace {

using detail::SoleRows;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Both patches of both feet of `pb`, each through both paths; and whether
// each foot is below a band over floors that put its lowest point on
// either side of the band's edge, by far and by an ulp.
void expect_same(const Body& body, const SoleRows& rows, const PosedBody& pb, const char* what) {
  const SoleSurface& sole = body.sole();
  for (const auto* foot : {&pb.left_foot, &pb.right_foot}) {
    for (const SolePatch& p : *foot) {
      const double ref = detail::patch_lowest_z(sole, p),
                   fast = detail::patch_lowest_z(sole, rows, p);
      ASSERT_TRUE(same_bits(ref, fast)) << what << ": reference " << ref << ", pruned " << fast;
    }
    const double lowest = detail::foot_lowest_z(sole, *foot);
    ASSERT_TRUE(same_bits(lowest, detail::foot_lowest_z(sole, rows, *foot))) << what;
    constexpr double kBand = 0.01;
    const double edge = lowest - kBand;  // the floor that puts the lowest point at the band's edge
    for (double floor :
         {0.0, -0.3, 0.3, edge, std::nextafter(edge, 1.0), std::nextafter(edge, -1.0), edge + 1e-9,
          edge - 1e-9, edge + 0.004, edge - 0.004})
      ASSERT_EQ(detail::foot_below(sole, rows, *foot, floor, kBand), lowest - floor < kBand)
          << what << ": lowest " << lowest << ", floor " << floor;
  }
}

// A patch turned by `turn` about its origin, then moved by `shift`.
SolePatch moved(SolePatch p, const Eigen::Matrix3d& turn, const Eigen::Vector3d& shift) {
  p.forward = turn * p.forward, p.left = turn * p.left, p.up = turn * p.up;
  p.origin += shift;
  return p;
}

std::vector<Body> bodies() {
  std::vector<Body> out;
  for (auto [sex, h, w] : {std::tuple{Sex::female, 140.0, 40.0},
                           {Sex::male, 205.0, 130.0},
                           {Sex::male, 175.0, 75.0}}) {
    BodySpec s;
    s.id = "b";
    s.sex = sex, s.height_cm = h, s.weight_kg = w;
    out.emplace_back(s);
  }
  return out;
}

TEST(SoleLowest, PrunedScanIsTheReferenceInEveryOrientation) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), small(-0.3, 0.3), z(-0.1, 0.4);
  for (const Body& body : bodies()) {
    const SoleRows rows(body.sole());
    const PosedBody rest = pose_body(body, test::rest_pose(body.spec().height_cm));
    expect_same(body, rows, rest, "rest");
    for (int k = 0; k < 4000; ++k) {
      // Any orientation (half the cases near level, as feet mostly are).
      const Eigen::Vector3d axis = Eigen::Vector3d(small(rng), small(rng), angle(rng)).normalized();
      const double a = k % 2 ? angle(rng) : 0.2 * small(rng);
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(a, axis).toRotationMatrix();
      const Eigen::Vector3d shift(small(rng), small(rng), z(rng));
      PosedBody pb = rest;
      for (auto* foot : {&pb.left_foot, &pb.right_foot})
        for (SolePatch& p : *foot) p = moved(p, turn, shift);
      expect_same(body, rows, pb, "turned");
    }
  }
}

TEST(SoleLowest, PrunedScanIsTheReferenceThroughAWalk) {
  for (const Body& body : bodies()) {
    const SoleRows rows(body.sole());
    GenerateOptions g;
    g.category = Category::walking;
    g.seconds = 4;
    g.height_cm = body.spec().height_cm;
    const Motion walk = generate_motion(g);
    ASSERT_GT(walk.size(), 60);
    for (const Pose& pose : walk.frames) expect_same(body, rows, pose_body(body, pose), "walk");
  }
}

TEST(SoleLowest, TiesAndValuesThatAreNotFinite) {
  const Body body = bodies()[2];
  const SoleRows rows(body.sole());
  PosedBody pb = pose_body(body, test::rest_pose(175));
  // A level sole: whole rows of equal heights, the first of them kept.
  for (auto* foot : {&pb.left_foot, &pb.right_foot})
    for (SolePatch& p : *foot)
      p.forward = Eigen::Vector3d(1, 0, 0), p.left = Eigen::Vector3d(0, 1, 0),
      p.up = Eigen::Vector3d(0, 0, 1), p.origin.z() = 0;
  expect_same(body, rows, pb, "level");
  pb.left_foot[0].origin.z() = -0.0;
  expect_same(body, rows, pb, "level at -0");
  // Not finite: the reference's own scan, whatever it makes of them.
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e308}) {
    PosedBody q = pb;
    q.left_foot[0].origin.z() = bad;
    q.right_foot[1].up.z() = bad;
    expect_same(body, rows, q, "not finite");
  }
  // A patch that covers no row of the table.
  SolePatch none = pb.left_foot[0];
  none.u_begin = 2, none.u_end = 3;
  EXPECT_EQ(detail::patch_lowest_z(body.sole(), rows, none), 1e300);
  EXPECT_EQ(detail::patch_lowest_z(body.sole(), none), 1e300);
}

TEST(SoleLowest, RowsHoldTheFootCells) {
  const Body body = bodies()[0];
  const SoleSurface& sole = body.sole();
  const SoleRows rows(sole);
  ASSERT_EQ(int(rows.first.size()), sole.nu);
  int with_cells = 0;
  for (int i = 0; i < sole.nu; ++i) {
    for (int j = 0; j < sole.nv; ++j) {
      const float h = sole.height_m[std::size_t(i) * std::size_t(sole.nv) + std::size_t(j)];
      const bool inside = h < SoleSurface::kOutside;
      if (j < rows.first[std::size_t(i)] || j > rows.last[std::size_t(i)])
        EXPECT_FALSE(inside) << i << ", " << j;
      if (inside) {
        EXPECT_GE(h, rows.h_lo[std::size_t(i)]);
        EXPECT_LE(h, rows.h_hi[std::size_t(i)]);
        EXPECT_LE(h, rows.h_abs);
      }
    }
    with_cells += rows.first[std::size_t(i)] <= rows.last[std::size_t(i)];
  }
  EXPECT_GT(with_cells, sole.nu / 2);
}

}  // namespace
}  // namespace ptnet
