// ptnet/io.hpp: small file helpers shared by every stage.
//
//   ptnet::AtomicFile out("data.h5", /*force=*/false);  // refuses to clobber
//   write_everything(out.temp_path());
//   out.commit();                                       // rename into place
//
// Outputs are written to a temporary file beside the target and renamed when
// complete, so a failed run never leaves a half-written file. Without force an
// existing target is an error.
#pragma once

#include <string>

namespace ptnet {

// Reads a whole file; throws Error naming the file when it cannot.
std::string read_text_file(const std::string& path);

// Throws Error if `path` exists and `force` is false, or if its folder is
// missing or not writable.
void check_output_path(const std::string& path, bool force);

class AtomicFile {
 public:
  AtomicFile(std::string path, bool force);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temp_path() const { return temp_; }
  const std::string& path() const { return path_; }
  void commit();  // renames the temporary file onto path()

 private:
  std::string path_, temp_;
  bool committed_ = false;
};

// Writes `text` to `path` atomically (see AtomicFile).
void write_text_file(const std::string& path, const std::string& text, bool force);

}  // namespace ptnet
