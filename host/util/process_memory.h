#pragma once
// How the program's memory is laid out: glibc's heap, tuned once at startup (host/cli/main.cpp) for a run
// that allocates large blocks and a few dozen threads.
#include <cstddef>
#include <cstdint>

namespace raycube::host {

// glibc maps every block of 128 KB or more afresh and unmaps it on free, and gives back the top of a heap
// beyond 128 KB: the next vector of that size faults its pages in again, which paravirtualised page tables
// make dear. Blocks up to 32 MB (glibc's largest threshold) come from the heaps instead, and freed memory
// stays for the next ones: fewer page faults and shorter runs, for a few MB more peak memory.
//
// And one heap for every thread: a thread's first allocation otherwise opens an arena of its own, whose
// pages all fault in afresh, where the main heap has the parser's freed memory to hand out. The host's
// preparation runs on threads it starts for a few milliseconds (the BVH's build, the sub-sample, the box
// trees), which on arenas of their own paid those faults again: a BVH built on such a thread took about
// twice as long as on the main one. The processors allocate little once running (overflow chunks, their
// local stacks' growth), so they do not queue for the one heap's lock.
void keepFreedMemory();

// The part of the heap on huge pages: [start, end), empty where the kernel refused.
struct HugePageHeap {
  std::uintptr_t start = 0, end = 0;
};

// And that heap on huge pages where the kernel offers them on request (transparent huge pages in "madvise"
// mode, as on this project's machine; harmless in "always" or "never"): a page fault per 2 MB instead of
// per 4 KB, each of them dear under paravirtualised page tables. The heap is
// extended by `reserve` at once (address space only: pages are still taken as they are first touched) and
// that part marked MADV_HUGEPAGE; growth beyond it gets ordinary pages. What glibc's tunable
// glibc.malloc.hugetlb=1 does, which can only be set in the environment before a program starts. Call
// after keepFreedMemory (blocks below its threshold come from this heap), before threads start.
HugePageHeap putHeapOnHugePages(std::size_t reserve = std::size_t(256) << 20);

}  // namespace raycube::host
