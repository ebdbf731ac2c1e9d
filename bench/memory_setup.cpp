// Every benchmark program starts as the command-line tool does (app/ptnet.cpp):
// freed memory kept by the C library (ptnet/memory.hpp), so that the figures
// are those of the tool, not of a page fault per tensor.
#include "ptnet/memory.hpp"

namespace {
const bool kFreedMemoryKept = (ptnet::keep_freed_memory(), true);
}  // namespace
