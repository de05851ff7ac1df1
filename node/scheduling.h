#pragma once
// Every scheduling constant of the machine in one place, with its reason (as core/tolerances.h does for
// numerical tolerances). None changes what is computed, only when: the image and the ray counts are the
// same for any value. They matter because 16 to 64 logical processors and a host share two cores.
#include <algorithm>
#include <chrono>
#include <cstddef>

namespace raycube::node::scheduling {

// Rays a node takes from its incoming FIFOs per step: enough to amortise a scan of its faces, few enough
// that its primaries and the token are not starved behind a long burst.
inline constexpr std::size_t kInboxBatch = 32;

// 3.5.2 back-pressure, as on the iPSC where a full FIFO locked the synthesis task: no new primary ray while
// more than this many rays wait for room in a neighbour's FIFO. Received rays are still consumed, so a
// cycle of full FIFOs always drains (2.2); the limit only bounds the overflow lists.
inline constexpr std::size_t kBacklogLimit = 64;

// The same across the machine where one memory holds it (node::BasicTransport::primariesHeld): no processor
// shoots a primary ray from the moment kMachineBacklogLimit rays wait in all the overflow lists together
// until fewer than half as many do. A processor's own limit leaves the others shooting, and the
// rays they spawn pile up in front of the busiest regions: mount 6 at 8 x 8 had 115,000 rays waiting at the
// lists' high waters and a 12 MB peak of them; peak memory 63.6 -> 53.8 MB with these, CPU unchanged
// (paired, 1.005). Limits of 2,048-4,096 saved 1-2 MB more and cost 4-6% of CPU: every release wakes the
// processors held back.
inline constexpr std::size_t kMachineBacklogLimit = 8192;
inline constexpr std::size_t machineBacklogRelease(std::size_t limit) {
  return std::max<std::size_t>(1, limit / 2);
}

// Where the scene lies, for a ray leaving its region (MachineContext::sceneBounds): this many world boxes
// at most. Every region exit tests them (a few nanoseconds each) to save some messages (most of a
// microsecond each). Messages at 8 x 8 with 1 / 4 / 16 boxes: rings 7 749 / 691 / 622 k, balls 4 322 /
// 294 / 258 k, mount 6 2.14 / 2.14 / 2.13 M, whose 2.1 M exits would pay 16 boxes' tests for nothing.
inline constexpr std::size_t kSceneBoundsBoxes = 4;

// Rays a face's FIFO holds on threads. The paper's FIFO queues "can store 128 rays" (3.5.2,
// queues::kPaperFifoCapacity): the emulated iPSC keeps them, with which its clock and section 3.6's
// saturation were measured, and so do MPI ranks, whose FIFO is a link's credits (measured at 128). Threads
// sharing two cores take 512: a processor waiting for room in a full FIFO gives its core to another thread,
// and 128 rays made short turns. Mount 6 at 512 x 512, 10 interleaved rounds, wall: 4 x 4 0.400 -> 0.370 s
// (image-parallel 0.270 s), 8 x 8 0.495 -> 0.450 s, context switches of a 4 x 4 run 11,000 -> 4,400; 256
// rays: 0.385 and 0.480 s. Paired 8 rounds at 8 x 8: balls 4 0.98, jacks 4 0.99, lattice 12 0.96, tetra
// 6 0.99 (its FIFOs' slots untouched, in one block: queues::SlotStorage). Peak memory 1-10 MB more, as
// rings cycle through their slots: jacks 4 at 8 x 8 25.9 -> 35.5 MB (224 rings of 64 KB), image-parallel's
// 19.1 MB.
inline constexpr std::size_t kThreadsFifoRays = 512;

// Primary rays a processor's thread shoots in one step when no ray arrived: its step's bookkeeping (a scan
// of its incoming FIFOs, its overflow lists, back-pressure, progress, ringing its neighbours) was 500
// instructions, as much as a segment's walk, paid once per primary ray on scenes where most rays are.
// Received rays still come first at every step, and back-pressure is asked before every primary. The
// emulated machine's steps shoot one, as the paper's synthesis task (3.5.2): its clock charges by step.
inline constexpr int kPrimariesPerStep = 8;

// Threads with FifoFull::Lock: how often the host looks for a cycle of processors locked on each other's
// full FIFOs, and how long such a cycle must stand with none of its processors stepping, its FIFOs full,
// before it is declared a deadlock. Proof needs only a period with no step: a locked processor whose FIFO
// has room is rung awake and steps; the period is long so that a thread the OS left unscheduled (64 of
// them share 2 cores) is not taken for a locked one, short so that the user hears of it within seconds.
inline constexpr auto kDeadlockPoll = std::chrono::milliseconds(50);
inline constexpr auto kDeadlockQuiet = std::chrono::milliseconds(1000);

// How a waiting thread waits: spin a little (a handoff from the other core), yield so the thread that
// would unblock it can run, then sleep on its doorbell.
struct SpinThenYield {
  int spins;
  int yields;
};
// A node: 64 nodes share 2 cores, so spinning long only steals the core from the node that would wake it.
inline constexpr SpinThenYield kNodeWait{4, 8};

// The host lets contribution blocks pile up this long between drains: one wake-up per batch of blocks,
// not per block, since the host thread shares the two cores with every processor.
inline constexpr auto kHostBatchingPause = std::chrono::microseconds(500);

// Contributions per block a node ships to the host (3.4), and blocks the processors of one host may have
// in flight before they wait: enough for the host's batching pause at the machine's peak rate, which the
// processors share. The peak is about 5 million contributions a second on this machine's 2 cores, 2,500 per
// pause, 10 blocks: 128 blocks (8 each at 4 x 4, 2 at 8 x 8) leave room for ten times that. Each block is
// 8 KB the queue touches as it cycles: 512 blocks cost jacks 4 at 4 x 4 a quarter of its peak memory (35.7 ->
// 27.5 MB with this and the BVH restriction's reserve), for no speed; a minimum of 4 per processor another
// 1 MB at 8 x 8 (mount 6 no slower with 2).
inline constexpr std::size_t kContributionBlock = 256;
inline constexpr std::size_t kContributionBlocksPerHost = 128;
inline constexpr std::size_t kMinContributionBlocks = 2;
inline constexpr std::size_t contributionBlocksPerProcessor(std::size_t processors) {
  return processors == 0 ? kMinContributionBlocks
                         : std::max(kMinContributionBlocks, kContributionBlocksPerHost / processors);
}

}  // namespace raycube::node::scheduling
