// keep_freed_memory(): glibc malloc told to reuse what it frees (memory.hpp).
#include "ptnet/memory.hpp"

#include <cstdlib>  // defines __GLIBC__ on the GNU C library
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ptnet {

// Below this size an allocation comes from the heap, not from its own
// mmap: a tensor of a chunk of 32 paper-width windows is 18 MB (the
// InferenceNet keeps its chunks below 20 MB, chunk_windows), a
// simulated sequence a few MB.
constexpr int kMmapBelowBytes = 32 << 20;  // glibc's largest (HEAP_MAX_SIZE / 2)
// Free memory at the top of a heap is handed back to the kernel only
// beyond this.
constexpr int kTrimAboveBytes = 1 << 30;

void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, kMmapBelowBytes);
  mallopt(M_TRIM_THRESHOLD, kTrimAboveBytes);
#endif
}

}  // namespace ptnet
