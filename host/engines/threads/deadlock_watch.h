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
  auto worked = [&](const std::vector<int>& cycle) {
    std::vector<std::uint64_t> w;
    for (int p : cycle) w.push_back(nodes[std::size_t(p)]->stepsWorked());
    return w;
  };
  std::vector<int> candidate;
  std::vector<std::uint64_t> candidateWorked;
  Clock::time_point since;
  std::vector<int> lockedOn(nodes.size());
  while (!stop()) {
    std::this_thread::sleep_for(node::scheduling::kDeadlockPoll);
    // Steps first, then locks: a processor whose count is the same later held this lock all along.
    std::vector<std::uint64_t> before;
    for (const auto& n : nodes) before.push_back(n->stepsWorked());
    for (std::size_t p = 0; p < nodes.size(); ++p) lockedOn[p] = nodes[p]->lockedOn();
    const std::vector<int> cycle = lockCycle(lockedOn);
    if (cycle.empty() || cycle != candidate) {
      candidate = cycle;
      candidateWorked.clear();
      for (int p : cycle) candidateWorked.push_back(before[std::size_t(p)]);
      since = Clock::now();
      continue;
    }
    if (Clock::now() - since < node::scheduling::kDeadlockQuiet) continue;
    bool full = true;
    for (std::size_t k = 0; k < cycle.size(); ++k)
      full = full && rays(cycle[k], cycle[(k + 1) % cycle.size()]) >= capacity;
    if (full && worked(cycle) == candidateWorked) {
      Deadlock deadlock = deadlockOf(cycle, regions, rays);
      deadlock.wallSeconds = secondsSince(start);
      return deadlock;
    }
    if (worked(cycle) != candidateWorked) candidate.clear();  // it moved: start over
  }
  return std::nullopt;
}

}  // namespace raycube::host
