// A marker map named in a list (a clips or trials CSV): a shipped map's
// name, or a file relative to the list's folder (ptnet/markers.hpp).
#include <algorithm>

#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"

namespace ptnet {

std::string marker_map_in(const std::string& folder, const std::string& name_or_path) {
  const std::vector<std::string> shipped = marker_map_names();
  if (std::find(shipped.begin(), shipped.end(), name_or_path) != shipped.end()) return name_or_path;
  return resolved_path(folder, name_or_path);
}

}  // namespace ptnet
