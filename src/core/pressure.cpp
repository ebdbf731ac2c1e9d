// Checks shared by every reader of pressure frames (ptnet/pressure.hpp).
#include <cmath>

#include "ptnet/error.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

void check_finite(const float* kpa, std::size_t n, int cells, const std::string& file, const std::string& what,
                  std::size_t first_frame) {
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(kpa[i]))
      throw Error::in(file, (what.empty() ? std::string() : what + ": ") +
                                "non-finite value (NaN or Inf) in frame " +
                                std::to_string(first_frame + i / std::size_t(cells > 0 ? cells : 1)));
}

}  // namespace ptnet
