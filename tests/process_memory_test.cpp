// The program's heap (host/util/process_memory.h): on huge pages where the kernel offers them, so that a
// large block faults in a few times rather than once per 4 KB page.
#include "host/util/process_memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace raycube::host {
namespace {

long minorFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// The kernel's transparent huge pages: "always", "madvise" or "never" (the bracketed word).
std::string hugePageMode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const std::size_t open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? ""
                                                                 : line.substr(open + 1, close - open - 1);
}

TEST(ProcessMemory, ALargeBlockOfTheHeapFaultsInHugePages) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers bring their own allocator";
#endif
  const std::string mode = hugePageMode();
  if (mode != "always" && mode != "madvise") GTEST_SKIP() << "no transparent huge pages here";
  keepFreedMemory();
  const HugePageHeap heap = putHeapOnHugePages(std::size_t(64) << 20);
  ASSERT_LT(heap.start, heap.end);
  EXPECT_EQ(heap.start % (std::uintptr_t(2) << 20), 0u);
  EXPECT_GE(heap.end - heap.start, std::uintptr_t(32) << 20);
  // A 16 MB block comes from the reserve; its 4 KB pages from the reserve's start on fault in 2 MB at a time.
  constexpr std::size_t kBlock = std::size_t(16) << 20;
  char* block = static_cast<char*>(std::malloc(kBlock));
  ASSERT_NE(block, nullptr);
  const auto first = std::max(reinterpret_cast<std::uintptr_t>(block), heap.start);
  const auto last = reinterpret_cast<std::uintptr_t>(block) + kBlock;
  ASSERT_LT(first, last);
  ASSERT_LE(last, heap.end);
  const long before = minorFaults();
  for (std::uintptr_t at = first; at < last; at += 4096) *reinterpret_cast<volatile char*>(at) = 1;
  const long faults = minorFaults() - before;
  const long pages = long((last - first) / 4096);
  // Where the kernel finds no free 2 MB page it falls back to small ones (a few hundred faults of 4,096,
  // seen with the test suite running beside): half the pages at most, where every page faulted without.
  EXPECT_LT(faults, pages / 2) << faults << " faults for " << pages << " pages of 4 KB";
  std::free(block);
}

}  // namespace
}  // namespace raycube::host
