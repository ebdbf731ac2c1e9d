// Placement of a sequence on the mat: centred, walking direction along the
// long axis (row 0 = the far end the body walks towards), the body's left
// towards col 0.
#include <algorithm>
#include <cmath>

#include "sim_internal.hpp"

namespace ptnet::detail {

std::vector<double> gaussian_smooth(const std::vector<double>& x, double sigma) {
  if (sigma < 0.3 || x.size() < 2) return x;
  const int n = int(x.size()), radius = int(std::ceil(3 * sigma));
  std::vector<double> k(2 * radius + 1);
  for (int i = -radius; i <= radius; ++i) k[i + radius] = std::exp(-0.5 * i * i / (sigma * sigma));
  std::vector<double> y(x.size());
  for (int t = 0; t < n; ++t) {
    double s = 0, w = 0;
    for (int i = std::max(-radius, -t); i <= std::min(radius, n - 1 - t); ++i) {
      s += k[i + radius] * x[t + i];
      w += k[i + radius];
    }
    y[t] = s / w;
  }
  return y;
}

MatPlacement place_on_mat(const Motion& motion, const SimOptions& options) {
  const int T = motion.size();
  MatPlacement out;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero(), facing = Eigen::Vector2d::Zero();
  for (const auto& pose : motion.frames) {
    mean += pose[kPelvis].head<2>();
    // Facing = (left hip - right hip) turned 90 degrees clockwise.
    Eigen::Vector2d lr = (pose[kLeftHip] - pose[kRightHip]).head<2>();
    Eigen::Vector2d f(lr.y(), -lr.x());
    if (f.norm() > 1e-9) facing += f.normalized();
  }
  mean /= T;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& pose : motion.frames) {
    Eigen::Vector2d d = pose[kPelvis].head<2>() - mean;
    cov += d * d.transpose();
  }
  cov /= T;
  // Major axis of the 2 x 2 covariance in closed form.
  const double a = cov(0, 0), b = cov(0, 1), c = cov(1, 1);
  const double angle = 0.5 * std::atan2(2 * b, a - c);
  Eigen::Vector2d axis(std::cos(angle), std::sin(angle));
  double lo = 1e300, hi = -1e300;
  for (const auto& pose : motion.frames) {
    double s = axis.dot(pose[kPelvis].head<2>() - mean);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  const bool moves = hi - lo > 0.3;  // m: less is standing / exercising in place
  if (!moves) {
    axis = facing.norm() > 1e-6 ? Eigen::Vector2d(facing.normalized()) : Eigen::Vector2d(1, 0);
  } else {
    // Point the axis the way the body travels (or faces, for a round trip).
    double travel = axis.dot((motion.frames.back()[kPelvis] - motion.frames.front()[kPelvis]).head<2>());
    double sign = std::abs(travel) > 0.1 ? travel : axis.dot(facing);
    if (sign < 0) axis = -axis;
  }
  out.axis = axis;
  out.left = Eigen::Vector2d(-axis.y(), axis.x());

  out.centre.assign(T, mean);
  if (options.placement == Placement::fixed) {
    // Centre of the pelvis path's bounding box in mat axes.
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& pose : motion.frames) {
      Eigen::Vector2d p = pose[kPelvis].head<2>();
      x0 = std::min(x0, out.axis.dot(p)), x1 = std::max(x1, out.axis.dot(p));
      y0 = std::min(y0, out.left.dot(p)), y1 = std::max(y1, out.left.dot(p));
    }
    Eigen::Vector2d c = 0.5 * (x0 + x1) * out.axis + 0.5 * (y0 + y1) * out.left;
    out.centre.assign(T, c);
  } else {
    std::vector<double> px(T), py(T);
    for (int t = 0; t < T; ++t) {
      px[t] = motion.frames[t][kPelvis].x();
      py[t] = motion.frames[t][kPelvis].y();
    }
    double sigma = options.follow_smoothing_s * motion.fps;
    px = gaussian_smooth(px, sigma);
    py = gaussian_smooth(py, sigma);
    for (int t = 0; t < T; ++t) out.centre[t] = Eigen::Vector2d(px[t], py[t]);
  }
  return out;
}

}  // namespace ptnet::detail
