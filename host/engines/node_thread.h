#pragma once
// A processor's thread, on any interconnect whose processors wait on doorbells (shared memory, MPI): step
// the node; when it has nothing to do, sleep until something arrives, and count the time asleep as blocked
// (rays held for a full neighbour) or idle.
#include <chrono>

#include "host/machine/machine_report.h"
#include "host/util/clock.h"
#include "node/logical_processor.h"
#include "node/scheduling.h"

namespace raycube::host {

template <class Real, class Interconnect>
void driveNodeThread(node::LogicalProcessor<Real>& node, Interconnect& interconnect, int id,
                     ProcessorReport& times) {
  for (;;) {
    const node::Step step = node.step(node::scheduling::kPrimariesPerStep);
    interconnect.ringNeighbours(id);
    if (step == node::Step::Terminated) return;
    if (step == node::Step::Worked) continue;
    const auto start = Clock::now();
    const bool blocked = node.blocked();
    interconnect.waitFor(id, [&] { return node.readyToStep(); });
    (blocked ? times.blockedSeconds : times.idleSeconds) += secondsSince(start);
  }
}

}  // namespace raycube::host
