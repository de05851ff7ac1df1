#pragma once
// A deadlock of the paper's flow control (node::FifoFull::Lock): a cycle of processors, each one's synthesis
// task locked on the full FIFO towards the next (Priol & Bouatouch 2.2 names the danger, 3.5.2 the lock).
// None of them takes a ray in while locked, so none of the FIFOs ever drains: the run is stopped and the
// deadlock reported as its result, never a hang.
#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/util/clock.h"
#include "node/region_map.h"

namespace raycube::host {

struct LockedFifo {
  int from = 0, to = 0;                // processors: `from` is locked on its FIFO towards `to`
  node::Face face = node::Face::Left;  // the face of `from`'s region the FIFO leaves through
  std::size_t rays = 0;                // rays in it when found (its capacity: full)
};

struct Deadlock {
  std::vector<LockedFifo> cycle;  // cycle[k].to == cycle[k + 1].from, the last back to the first
  // Emulated time: when the last processor of the cycle locked (the deadlock's instant); -1 on threads.
  double simulatedSeconds = -1;
  double wallSeconds = -1;  // threads: how long the run had gone when the deadlock was proved
};

// The first cycle in the graph where processor p waits for lockedOn[p] (-1: for no one), in the order of
// the waits, starting from its lowest-numbered processor; empty when there is none.
std::vector<int> lockCycle(const std::vector<int>& lockedOn);

// The proof of a deadlock from looks at a running machine, the way an engine can take them (threads: the
// processors' atomics; MPI: the progress the ranks report): a cycle of lockCycle that held, every processor
// of it doing nothing (no step worked: no ray taken in, none sent), for `quiet` on end. None of them took a
// ray in, so none of the FIFOs between them drained, and the sender of each was still locked on it: each
// waits for the next, which waits in turn, for good.
class DeadlockProof {
 public:
  explicit DeadlockProof(std::chrono::milliseconds quiet) : quiet_(quiet) {}
  // One look: whom each processor is locked on (-1: no one) and its steps that worked, seen at `now`.
  // Returns the cycle once proved, else empty.
  std::vector<int> look(const std::vector<int>& lockedOn, const std::vector<std::uint64_t>& stepsWorked,
                        Clock::time_point now);

 private:
  std::chrono::milliseconds quiet_;
  std::vector<int> candidate_;
  std::vector<std::uint64_t> candidateWorked_;
  Clock::time_point since_;
};

// The FIFOs of a cycle of lockCycle, with their faces; rays(from, to) says how many rays each holds.
template <class RaysIn>
Deadlock deadlockOf(const std::vector<int>& cycle, const node::RegionMap& regions, RaysIn&& rays) {
  Deadlock d;
  for (std::size_t k = 0; k < cycle.size(); ++k) {
    const int from = cycle[k], to = cycle[(k + 1) % cycle.size()];
    d.cycle.push_back({from, to, regions.faceToward(from, to), rays(from, to)});
  }
  return d;
}

// "processors 3 -> 7 -> 3 locked on full FIFOs (3 right 128 rays, 7 left 128 rays) at 12.5 simulated s":
// what the user reads.
std::string describe(const Deadlock& deadlock);

// What renderMachine throws when the machine deadlocked; the report it filled holds the deadlock and the
// counts up to it, for --stats.
class MachineDeadlocked : public std::runtime_error {
 public:
  explicit MachineDeadlocked(const Deadlock& deadlock) : std::runtime_error(describe(deadlock)) {}
};

}  // namespace raycube::host
