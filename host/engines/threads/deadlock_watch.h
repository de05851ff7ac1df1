#pragma once
// The threads engine's proof of a deadlock under node::FifoFull::Lock: a cycle of processors, each locked
// on the full FIFO towards the next, none of them stepping for scheduling::kDeadlockQuiet. No processor of
// the cycle took a ray in during that time (taking one is a step), so none of its FIFOs drained; each was
// full when looked at last, so each was full throughout, and stays so. Looked at from the host's side, by
// polling what every processor publishes (LogicalProcessor::lockedOn, stepsWorked).
#include <chrono>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "host/machine/deadlock.h"
#include "host/util/clock.h"
#include "node/logical_processor.h"
#include "node/scheduling.h"

namespace raycube::host {

// Polls until stop() holds (returns none) or a deadlock is proved (returns it). rays(from, to): rays in
// the FIFO from processor `from` to its neighbour `to`, read from this thread.
template <class Real, class RaysIn, class Stop>
std::optional<Deadlock> watchForDeadlock(
    const std::vector<std::unique_ptr<node::LogicalProcessor<Real>>>& nodes, const node::RegionMap& regions,
    std::size_t capacity, RaysIn&& rays, Stop&& stop) {
  const auto start = Clock::now();
  DeadlockProof proof(
      std::chrono::duration_cast<std::chrono::milliseconds>(node::scheduling::kDeadlockQuiet));
  std::vector<int> lockedOn(nodes.size());
  std::vector<std::uint64_t> worked(nodes.size());
  while (!stop()) {
    std::this_thread::sleep_for(node::scheduling::kDeadlockPoll);
    // Steps first, then locks: a processor whose count is the same later held this lock all along.
    for (std::size_t p = 0; p < nodes.size(); ++p) worked[p] = nodes[p]->stepsWorked();
    for (std::size_t p = 0; p < nodes.size(); ++p) lockedOn[p] = nodes[p]->lockedOn();
    const std::vector<int> cycle = proof.look(lockedOn, worked, Clock::now());
    if (cycle.empty()) continue;
    bool full = true;
    for (std::size_t k = 0; k < cycle.size(); ++k)
      full = full && rays(cycle[k], cycle[(k + 1) % cycle.size()]) >= capacity;
    if (!full) continue;
    Deadlock deadlock = deadlockOf(cycle, regions, rays);
    deadlock.wallSeconds = secondsSince(start);
    return deadlock;
  }
  return std::nullopt;
}

}  // namespace raycube::host
