// keep_freed_memory() (ptnet/memory.hpp): blocks freed and taken again, as a
// training step's tensors are, come back without page faults. By default
// glibc hands the freed top of its heap back to the kernel (its trim
// threshold follows the largest block, a few MB), so each round faults in
// every page again: ~9,000 faults a round of this test.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "ptnet/memory.hpp"

namespace ptnet {
namespace {

long page_faults() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return r.ru_minflt;
}

// Page faults of `rounds` rounds of: 8 blocks of 1..8 MB (36 MB) taken and
// written, then all freed.
long faults_of_rounds(int rounds) {
  const long before = page_faults();
  for (int round = 0; round < rounds; ++round) {
    std::vector<void*> blocks;
    for (std::size_t mb = 1; mb <= 8; ++mb) {
      void* p = std::malloc(mb << 20);
      if (!p) return -1;
      std::memset(p, 1, mb << 20);
      blocks.push_back(p);
    }
    for (void* p : blocks) std::free(p);
  }
  return page_faults() - before;
}

TEST(CoreMemory, FreedBlocksAreTakenAgainWithoutPageFaults) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer has its own allocator";
#else
  keep_freed_memory();
  faults_of_rounds(2);  // the heap grows to its size once
  const int rounds = 10;
  const long faults = faults_of_rounds(rounds);
  ASSERT_GE(faults, 0) << "out of memory";
  // 36 MB a round is 9,216 pages: the default faults every one of them.
  EXPECT_LT(faults, 100 * rounds) << faults / rounds << " page faults a round";
#endif
}

}  // namespace
}  // namespace ptnet
