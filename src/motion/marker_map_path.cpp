// A marker map named in a list (a clips or trials CSV): a shipped map's
// name, or a file relative to the list's folder (ptnet/markers.hpp).
#include <algorithm>

#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

std::string marker_map_in(const std::string& list, long line, const std::string& folder,
                          const std::string& name_or_path) {
  const std::vector<std::string> shipped = marker_map_names();
  if (std::find(shipped.begin(), shipped.end(), name_or_path) != shipped.end()) return name_or_path;
  return listed_input(list, line, "marker_map", folder, name_or_path, " (shipped maps: " + join(shipped, ", ") + ")");
}

}  // namespace ptnet
