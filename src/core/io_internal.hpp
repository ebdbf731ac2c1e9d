// core/io_internal.hpp (private to the core stage; tests include it as
// "core/io_internal.hpp"): what io.cpp uses beside the public file helpers
// (ptnet/io.hpp).
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

}  // namespace ptnet
