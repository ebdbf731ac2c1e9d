// The model folder before and after a failed setup (model_folder.hpp).
#include "model_folder.hpp"

#include <exception>
#include <filesystem>

#include "ptnet/error.hpp"

namespace ptnet {
namespace fs = std::filesystem;

void prepare_out_dir(const std::string& dir, const TrainOptions& o) {
  std::error_code ec;
  if (o.resume) {
    if (!fs::is_directory(dir, ec))
      throw Error::in(dir, "no model folder to resume", ErrorKind::not_found);
    return;
  }
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) throw Error::in(dir, "exists and is not a folder");
    const bool empty = fs::is_empty(dir, ec);
    if (!empty && !o.force)
      throw Error::in(dir,
                      "exists; pass " + field_text("force") + " to overwrite or " +
                          field_text("resume") + " to continue",
                      ErrorKind::exists);
    for (const char* f : ModelFiles::kAll) fs::remove(ModelFiles(dir).path(f), ec);
  } else {
    fs::path parent = fs::path(dir).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
      throw Error::in(dir, "folder " + parent.string() + " does not exist", ErrorKind::not_found);
    if (!fs::create_directory(dir, ec))
      throw Error::in(dir, "cannot create folder: " + ec.message(), ErrorKind::io);
  }
}

LeftoverGuard::~LeftoverGuard() {
  if (!active_ || std::uncaught_exceptions() == 0) return;
  std::error_code ec;
  const ModelFiles files(dir_);
  if (fs::exists(files.weights(), ec)) return;
  for (const char* f : {ModelFiles::kConfig, ModelFiles::kCheckpoint, ModelFiles::kHistory}) fs::remove(files.path(f), ec);
  if (fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

}  // namespace ptnet
