// Gaussian smoothing of a series (core/smooth.hpp).
#include "core/smooth.hpp"

#include <algorithm>
#include <cmath>

namespace ptnet {

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

}  // namespace ptnet
