// FNV-1a 64 (core/hash.hpp).
#include "core/hash.hpp"

#include <cstdio>

namespace ptnet {

std::string Fnv1a::hex() const {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h_));
  return text;
}

}  // namespace ptnet
