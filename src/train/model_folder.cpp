// The model folder before and after a failed setup (model_folder.hpp).
#include "model_folder.hpp"

#include <exception>
#include <filesystem>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
namespace fs = std::filesystem;

void check_out_dir(const std::string& dir, const TrainOptions& o) {
  std::error_code ec;
  if (o.resume) {
    if (!fs::is_directory(dir, ec))
      throw Error::in(dir, "no model folder to resume", ErrorKind::not_found);
    return;
  }
  if (existing_folder(dir)) {
    if (!o.force && !fs::is_empty(dir, ec)) throw exists_error(dir, field_text("resume") + " to continue");
  } else {
    fs::path parent = fs::path(dir).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
      throw Error::in(dir, "folder " + parent.string() + " does not exist", ErrorKind::not_found);
  }
}

void prepare_out_dir(const std::string& dir, const TrainOptions& o) {
  check_out_dir(dir, o);
  if (o.resume) return;
  std::error_code ec;
  if (existing_folder(dir))
    for (const char* f : ModelFiles::kAll) fs::remove(ModelFiles(dir).path(f), ec);
  else
    make_folder(dir);
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
