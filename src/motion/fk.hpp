// Internal: the precomputed channel layout behind forward_kinematics().
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ptnet/motion.hpp"
#include "rotation.hpp"

namespace ptnet::detail {

class FkLayout {
 public:
  FkLayout(const Bvh& bvh, double scale);  // scale: metres per file unit
  // One frame: positions [J] in file axes (scaled), optional global
  // rotations [J] (file axes). No allocation after the first call.
  void run(const double* frame, Eigen::Vector3d* positions,
           Eigen::Matrix3d* rotations = nullptr) const;

 private:
  struct Layout {
    int parent = -1;
    double offset[3] = {0, 0, 0};
    int pos_col[3] = {-1, -1, -1};
    int rotations = 0;
    int rot_axis[3] = {0, 0, 0};
    int rot_col[3] = {0, 0, 0};
  };
  struct Frame {
    double p[3];
    double r[9];
  };
  std::vector<Layout> joints_;
  double scale_;
  mutable std::vector<Frame> scratch_;
};

}  // namespace ptnet::detail
