// ptnet/memory.hpp: how the process hands memory back to the kernel.
//
//   int main(int argc, char** argv) {
//     ptnet::keep_freed_memory();  // first thing: the C library keeps what is freed
//     ...
//   }
#pragma once

namespace ptnet {

// Tells the C library (glibc malloc) to keep the memory the program frees
// and reuse it, instead of handing each large block back to the kernel and
// faulting fresh zeroed pages in for the next one: no block of its own
// (mmap) below 32 MB, no trimming of a heap below 1 GiB free. A training
// step or a chunk of inference allocates and frees the same few MB of
// tensors again and again; on a virtual machine, where a page fault is
// slow, the faults took more CPU than the arithmetic (docs/model.md,
// "Speed": the demo's training 3x faster in wall time). The peak
// memory is about the same; what is freed stays with the process until it
// ends. Process-wide, so the library never calls it: the command-line tool
// and the benchmarks do, first thing in main(). Does nothing on another C
// library.
void keep_freed_memory();

}  // namespace ptnet
