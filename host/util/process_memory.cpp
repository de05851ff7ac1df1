#include "host/util/process_memory.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdlib>

namespace raycube::host {

void keepFreedMemory() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_ARENA_MAX, 1);
}

HugePageHeap putHeapOnHugePages(std::size_t reserve) {
  constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;
  mallopt(M_TOP_PAD, int(std::min<std::size_t>(reserve, INT_MAX)));
  // A block larger than what is left of the heap makes malloc extend it by the reserve, which stays
  // (volatile: the compiler may drop a malloc whose block is never used).
  void* volatile probe = std::malloc(std::size_t(1) << 20);
  std::free(probe);
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t start = (end - mallinfo2().arena + kHugePage - 1) / kHugePage * kHugePage;
  if (start >= end || madvise(reinterpret_cast<void*>(start), end - start, MADV_HUGEPAGE) != 0) return {};
  return {start, end};
}

}  // namespace raycube::host
