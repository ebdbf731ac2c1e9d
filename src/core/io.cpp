#include "ptnet/io.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ptnet/error.hpp"

namespace ptnet {
namespace fs = std::filesystem;

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error::in(path, "no such file");
  if (fs::is_directory(path, ec)) throw Error::in(path, "is a folder, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error::in(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error::in(path, "read error");
  return ss.str();
}

void check_output_path(const std::string& path, bool force) {
  std::error_code ec;
  if (fs::exists(path, ec) && !force)
    throw Error::in(path, "exists; pass --force to overwrite");
  fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) parent = ".";
  if (!fs::is_directory(parent, ec)) throw Error::in(path, "folder " + parent.string() + " does not exist");
  if (::access(parent.c_str(), W_OK) != 0) throw Error::in(path, "folder " + parent.string() + " is not writable");
}

AtomicFile::AtomicFile(std::string path, bool force) : path_(std::move(path)) {
  check_output_path(path_, force);
  fs::path p(path_);
  temp_ = (p.parent_path() / ("." + p.filename().string() + ".tmp" + std::to_string(::getpid()))).string();
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(temp_, path_, ec);
  if (ec) throw Error::in(path_, "cannot rename temporary file into place: " + ec.message());
  committed_ = true;
}

void write_text_file(const std::string& path, const std::string& text, bool force) {
  AtomicFile out(path, force);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    if (!f) throw Error::in(path, std::string("cannot write: ") + std::strerror(errno));
    f << text;
    f.flush();
    if (!f) throw Error::in(path, "write failed (disk full?)");
  }
  out.commit();
}

}  // namespace ptnet
