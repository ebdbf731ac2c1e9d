// Files a user names: a list's file checked at its line, an output's name
// checked against the format written (ptnet/io.hpp).
#include <filesystem>
#include <string>

#include "core/io_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

std::string listed_input(const std::string& list, long line, const std::string& column, const std::string& folder,
                         const std::string& name, const std::string& hint) {
  if (name.empty()) return "";
  const std::string path = resolved_path(folder, name);
  ErrorKind kind{};
  if (const std::string problem = input_file_problem(path, &kind); !problem.empty())
    throw Error(list + ":" + std::to_string(line) + ": " + column + " " + escaped(name) + ": " + problem + hint, kind);
  note_input(path);
  return path;
}

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
