// Files a user names: an output's name checked against the format written
// (ptnet/io.hpp).
#include <filesystem>
#include <string>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

void check_output_name(const std::string& path, std::initializer_list<const char*> extensions,
                       const std::string& written) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  std::string names;
  std::size_t k = 0;
  for (const char* e : extensions) {
    if (ext == e) return;
    names += std::string(k == 0 ? "" : k + 1 == extensions.size() ? " or " : ", ") + e;
    ++k;
  }
  throw Error::in(path, "expected a " + names + " file name (" + written + " is written), found " +
                            (ext.empty() ? std::string("no extension") : escaped(ext)));
}

}  // namespace ptnet
