// Internal: the plantar sole surface of a body (see ptnet/body.hpp).
#pragma once

#include "ptnet/body.hpp"

namespace ptnet::detail {

// The sole height table of a body of this sex, height and weight.
SoleSurface make_sole_surface(const BodySpec& spec);

}  // namespace ptnet::detail
