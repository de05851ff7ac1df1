#include "host/engines/threads/threaded_machine.h"

#include <latch>
#include <thread>

#include "host/engines/node_thread.h"
#include "host/util/parallel_for.h"
#include "host/engines/processor_thread.h"
#include "host/engines/threads/deadlock_watch.h"
#include "node/scheduling.h"
#include "queues/interconnects/jitter_transport.h"
#include "queues/interconnects/shared_memory_interconnect.h"

namespace raycube::host {

template <class Real>
MachineRun ThreadedMachine<Real>::run(const node::MachineContext& context, std::vector<node::NodeSetup> setups,
                                      const EngineHooks& hooks) {
  const int processors = int(setups.size());
  queues::SharedMemoryInterconnect<Real> interconnect(context.regions, queueCapacity_, backlogLimit_);
  std::vector<std::unique_ptr<queues::JitterTransport<Real>>> jitters;
  std::vector<node::BasicTransport<Real>*> transports;
  for (int id = 0; id < processors; ++id) {
    transports.push_back(&interconnect.endpoint(id));
    if (jitterSeed_ > 0) {
      jitters.push_back(
          std::make_unique<queues::JitterTransport<Real>>(*transports.back(), jitterSeed_ * 7919u + unsigned(id)));
      transports.back() = jitters.back().get();
    }
  }
  // 3.2 steps 2-3: every processor subdivides its region into cells, on the host's cores (64 threads doing
  // so at once on two cores took a third longer: sombrero 3 at 8 x 8, 11-17 -> 9-10 ms); when all have done
  // so, their threads start and the host lets the synthesis phase begin.
  std::vector<std::unique_ptr<node::LogicalProcessor<Real>>> nodes(setups.size());
  parallelFor(processors, [&](int id) {
    nodes[id] =
        std::make_unique<node::LogicalProcessor<Real>>(context, std::move(setups[id]), *transports[id]);
  });
  std::vector<ProcessorReport> reports(setups.size());
  std::latch synthesis(1);
  ProcessorThreads threads;
  for (int id = 0; id < processors; ++id)
    threads.start([&, id] {
      synthesis.wait();
      driveNodeThread(*nodes[id], interconnect, id, reports[id]);
    });
  if (hooks.synthesisStarts) hooks.synthesisStarts();
  synthesis.count_down();
  // --fifo-full lock: a deadlock is proved from here, and stops the machine as termination would.
  std::optional<Deadlock> deadlock;
  std::thread watch;
  if (context.fifoFull == node::FifoFull::Lock)
    watch = std::thread([&] {
      deadlock = watchForDeadlock(
          nodes, context.regions, queueCapacity_,
          [&](int from, int to) { return interconnect.raysIn(from, to); },
          [&] { return interconnect.terminated(); });
      if (deadlock) interconnect.endpoint(0).announceTermination();
    });
  // The host thread (3.5.1): accumulate contributions until the ring has proved termination.
  queues::ContributionChannel& channel = interconnect.hostChannel();
  auto accumulate = [&](const core::Contribution& c) { hooks.host->add(c); };
  std::vector<std::uint64_t> evaluated(nodes.size());
  while (!interconnect.terminated()) {
    channel.drain(accumulate);
    if (hooks.progress) {
      for (std::size_t p = 0; p < nodes.size(); ++p) evaluated[p] = nodes[p]->segmentsEvaluated();
      hooks.progress(evaluated);
    }
    std::this_thread::sleep_for(node::scheduling::kHostBatchingPause);
    queues::waitUntil(channel.doorbell(), [&] { return interconnect.terminated() || channel.anyPending(); });
  }
  threads.joinAll();
  if (watch.joinable()) watch.join();
  channel.drain(accumulate);
  for (int id = 0; id < processors; ++id) {
    reports[id].node = nodes[id]->stats();
    for (int f = 0; f < node::kFaces; ++f) reports[id].outgoing[f] = interconnect.outgoingStats(id, node::Face(f));
  }
  MachineRun run;
  run.processors = std::move(reports);
  run.deadlock = std::move(deadlock);
  return run;
}

template class ThreadedMachine<float>;
template class ThreadedMachine<double>;

}  // namespace raycube::host
