// core/body_spec_internal.hpp (private to the core stage; tests and fuzzers
// include it as "core/body_spec_internal.hpp"): the steps behind
// read_bodies_csv and draw_paper_body (ptnet/body_spec.hpp).
#pragma once

#include <random>
#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"

namespace ptnet {

// read_bodies_csv on CSV text (`source` names it in messages).
std::vector<BodySpec> parse_bodies_csv(const std::string& text, const std::string& source);

// Standard normal by Box-Muller on raw 53-bit uniforms: the same numbers on
// every platform (std::normal_distribution is implementation-defined).
double standard_normal(std::mt19937_64& rng);

}  // namespace ptnet
