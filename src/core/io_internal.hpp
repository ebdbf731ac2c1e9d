// core/io_internal.hpp (private to the core stage; tests include it as
// "core/io_internal.hpp"): what io.cpp uses beside the public file helpers
// (ptnet/io.hpp).
#pragma once

#include <cstdint>
#include <string>

#include "ptnet/error.hpp"

namespace ptnet {

// The error of an input that cannot be opened, from its errno: "no such
// file" (ErrorKind::not_found) or "cannot open: REASON" (ErrorKind::io).
Error open_error(const std::string& path, int err);

// Bytes of memory available to this process now (MemAvailable), or 0 if unknown.
std::uint64_t available_memory_bytes();

}  // namespace ptnet
