// Text read line by line (ptnet/io.hpp: LineReader): one block of the file
// and the longest line in memory, each line checked as UTF-8 before use.
#include <memory>

#include "core/io_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

LineReader::LineReader(const std::string& path, std::uint64_t max_bytes)
    : source_(path), file_(std::make_unique<InputFile>(path)), max_bytes_(max_bytes) {
  if (file_->size() > max_bytes)
    throw Error::in(path, bytes_text(file_->size()) + ", more than the " + bytes_text(max_bytes) +
                              " this kind of file may have");
}

LineReader::LineReader(std::string_view text, std::string source)
    : source_(std::move(source)), text_(text), end_(true) {}

LineReader::~LineReader() = default;

bool LineReader::fill() {
  if (end_) return false;
  constexpr std::size_t kBlock = std::size_t(1) << 16;
  const std::size_t left = text_.size();
  buffer_.erase(0, buffer_.size() - left);  // what is left moves to the front
  buffer_.resize(left + kBlock);
  const std::size_t got = file_->read(buffer_.data() + left, kBlock);
  buffer_.resize(left + got);
  text_ = buffer_;
  read_ += got;
  if (read_ > max_bytes_)
    throw Error::in(source_, "more than the " + bytes_text(max_bytes_) + " this kind of file may have (it grew while read)");
  end_ = got == 0;
  return got > 0;
}

bool LineReader::next(std::string_view& line) {
  std::size_t nl;
  while ((nl = text_.find('\n')) == std::string_view::npos) {
    if (text_.size() > kMaxLineBytes)
      throw Error::at(source_, number_ + 1, "lines of at most " + bytes_text(kMaxLineBytes), "a longer one");
    if (!fill()) break;
  }
  if (text_.empty() && end_) return false;
  line = text_.substr(0, nl);  // the whole rest when the last line has no end
  text_.remove_prefix(nl == std::string_view::npos ? text_.size() : nl + 1);
  if (line.size() > kMaxLineBytes)
    throw Error::at(source_, number_ + 1, "lines of at most " + bytes_text(kMaxLineBytes), "a longer one");
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (++number_ == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
  check_utf8(line, source_, number_);
  return true;
}

}  // namespace ptnet
