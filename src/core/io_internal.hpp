// core/io_internal.hpp (private to the core stage; tests include it as
// "core/io_internal.hpp"): what io.cpp and named_files.cpp use beside the
// public file helpers (ptnet/io.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "ptnet/error.hpp"

namespace ptnet {

// Throws Error "SOURCE:LINE: expected UTF-8 text, found byte 0xE9 (...)"
// (kind format) unless `text` is UTF-8 (utf8_invalid_at, strings.hpp; a
// byte-order mark is); `first_line` numbers text's first line. The one check
// of every reader of text files: read_text_file calls it before
// their caller sees any of the text. Defined in strings.cpp.
void check_utf8(std::string_view text, const std::string& source, long first_line = 1);

// Bytes of memory available to this process now: MemAvailable, and no more
// than its address-space limit leaves (RLIMIT_AS, `ulimit -v`); 0 if unknown.
std::uint64_t available_memory_bytes();

// What keeps InputFile from opening `path`, in its words ("no such file",
// "is a FIFO, expected a regular file", "is a folder, expected a file"),
// and its kind; "" when it opens. A list's files are checked so, at their
// line, by listed_input (ptnet/io.hpp).
std::string input_file_problem(const std::string& path, ErrorKind* kind = nullptr);

// `file` named in a list (a CSV) whose paths are relative to `folder`: as it
// is when empty or absolute, else folder / file, never normalised as text
// (the filesystem resolves "link/../x.trc" through the link, as the shell).
std::string resolved_path(const std::string& folder, const std::string& file);

}  // namespace ptnet
