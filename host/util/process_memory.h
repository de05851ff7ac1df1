#pragma once
// How the program's memory is laid out: glibc's heap, tuned once at startup (host/cli/main.cpp) for a run that
// allocates large blocks and a few dozen threads.
#include <cstddef>
#include <cstdint>

namespace raycube::host {

// glibc maps every block of 128 KB or more afresh and unmaps it on free, and gives back the top of a heap
// beyond 128 KB: the next vector of that size faults its pages in again, at about 10 us a page on this
// project's machine (paravirtualised page tables; 0.1-0.3 us on bare metal). Blocks up to 32 MB (glibc's
// largest threshold) come from the heaps instead, and freed memory stays for the next ones. Mount 6 at
// 512 x 512, paired against glibc's defaults: wall 0.95 image-parallel, 0.95 machine 4 x 4, 0.93 8 x 8 (page
// faults 7.6 -> 6.8 k, 11.0 -> 8.6 k); peak memory 2-9 MB more on the SPD's default sizes (sombrero 3: 38 ->
// 44 MB image-parallel, 52 -> 61 MB at 4 x 4).
//
// And one heap for every thread: a thread's first allocation otherwise opens an arena of its own, whose
// pages all fault in afresh, where the main heap has the parser's freed memory to hand out. The host's
// preparation runs on threads it starts for a few milliseconds (the BVH's build, the sub-sample, the box
// trees): sombrero 3's BVH took 29 ms built on such a thread, 14 ms on the main one. Paired against 16
// arenas, 8 rounds, wall: sombrero 3 at 4 x 4 0.89 (preprocessing 76 -> 45 ms), image-parallel 0.96; mount 6
// at 4 x 4 0.98, 8 x 8 1.00, image-parallel 1.02; jacks 4 at 8 x 8 1.00. The processors allocate little once
// running (overflow chunks, their local stacks' growth), so they do not queue for the one heap's lock.
void keepFreedMemory();

// The part of the heap on huge pages: [start, end), empty where the kernel refused.
struct HugePageHeap {
  std::uintptr_t start = 0, end = 0;
};

// And that heap on huge pages where the kernel offers them on request (transparent huge pages in "madvise"
// mode, as on this project's machine; harmless in "always" or "never"): a page fault per 2 MB instead of
// per 4 KB, which here cost 12.5 us each (a frame buffer of 12.6 MB: 3,100 faults, 39 ms). The heap is
// extended by `reserve` at once (address space only: pages are still taken as they are first touched) and
// that part marked MADV_HUGEPAGE; growth beyond it gets ordinary pages. What glibc's tunable
// glibc.malloc.hugetlb=1 does, which can only be set in the environment before a program starts. Call
// after keepFreedMemory (blocks below its threshold come from this heap), before threads start.
HugePageHeap putHeapOnHugePages(std::size_t reserve = std::size_t(256) << 20);

}  // namespace raycube::host
