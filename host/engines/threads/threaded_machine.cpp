#include "host/engines/threads/threaded_machine.h"

#include <cstdio>
#include <cstdlib>
#include <latch>
#include <stdexcept>
#include <string>
#include <thread>

#include "host/engines/node_thread.h"
#include "host/engines/processor_thread.h"
#include "host/engines/stall_watch.h"
#include "host/engines/threads/deadlock_watch.h"
#include "host/util/parallel_for.h"
#include "node/scheduling.h"
#include "queues/interconnects/jitter_transport.h"
#include "queues/interconnects/shared_memory_interconnect.h"
#include "queues/interconnects/step_stalling_transport.h"
#include "queues/interconnects/token_losing_transport.h"

namespace raycube::host {

namespace {

// "3, 7": the processors inside a step now.
template <class Nodes>
std::string steppingProcessors(const Nodes& nodes) {
  std::string list;
  for (std::size_t p = 0; p < nodes.size(); ++p)
    if (nodes[p]->stepping()) list += (list.empty() ? "" : ", ") + std::to_string(p);
  return list;
}

// What each processor holds, once their threads have been joined.
template <class Nodes>
std::string heldWork(const Nodes& nodes) {
  std::string held;
  for (std::size_t p = 0; p < nodes.size(); ++p)
    held += (p == 0 ? "processor " : "; processor ") + std::to_string(p) + " holds " +
            nodes[p]->describeHeldWork();
  return held;
}

[[noreturn]] void endStuck(const std::string& headline, const std::string& busy) {
  std::fprintf(
      stderr, "raycube: %s; processor %s has been inside one step all that time (a walk that does not end)\n",
      headline.c_str(), busy.c_str());
  std::fflush(stderr);
  std::_Exit(3);
}

}  // namespace

template <class Real>
MachineRun ThreadedMachine<Real>::run(const node::MachineContext& context,
                                      std::vector<node::NodeSetup> setups, const EngineHooks& hooks) {
  const int processors = int(setups.size());
  queues::SharedMemoryInterconnect<Real> interconnect(context.regions, queueCapacity_, backlogLimit_);
  std::vector<std::unique_ptr<node::BasicTransport<Real>>> wrappers;
  std::vector<node::BasicTransport<Real>*> transports;
  for (int id = 0; id < processors; ++id) {
    transports.push_back(&interconnect.endpoint(id));
    if (jitterSeed_ > 0) {
      wrappers.push_back(std::make_unique<queues::JitterTransport<Real>>(*transports.back(),
                                                                         jitterSeed_ * 7919u + unsigned(id)));
      transports.back() = wrappers.back().get();
    }
    if (loseTheToken_) {
      wrappers.push_back(std::make_unique<queues::TokenLosingTransport<Real>>(*transports.back()));
      transports.back() = wrappers.back().get();
    }
    if (stallAStep_ && id == processors - 1) {
      wrappers.push_back(std::make_unique<queues::StepStallingTransport<Real>>(*transports.back()));
      transports.back() = wrappers.back().get();
    }
  }
  // 3.2 steps 2-3: every processor subdivides its region into cells, on the host's cores (64 threads doing
  // so at once on two cores took longer, competing for them); when all have done
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
  std::thread deadlockWatch;
  if (context.fifoFull == node::FifoFull::Lock)
    deadlockWatch = std::thread([&] {
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
  StallWatch stallWatch(nodes.size(), stallPeriod_);
  while (!interconnect.terminated()) {
    channel.drain(accumulate);
    if (hooks.progress) {
      for (std::size_t p = 0; p < nodes.size(); ++p) evaluated[p] = nodes[p]->segmentsEvaluated();
      hooks.progress(evaluated);
    }
    std::this_thread::sleep_for(node::scheduling::kHostBatchingPause);
    queues::waitUntilFor(
        channel.doorbell(), [&] { return interconnect.terminated() || channel.anyPending(); },
        stallLookEvery(stallPeriod_));
    if (!interconnect.terminated() &&
        stallWatch.stalled([&](std::size_t p) { return nodes[p]->stepsWorked(); })) {
      // A processor inside a step all that time cannot be stopped, nor its thread joined: the program ends.
      if (const std::string busy = steppingProcessors(nodes); !busy.empty())
        endStuck(stallWatch.headline(), busy);
      interconnect.stop();
      threads.joinAll();
      if (deadlockWatch.joinable()) deadlockWatch.join();
      throw std::runtime_error(
          stallWatch.headline() +
          "; every processor waits (a ray or the termination token lost): " + heldWork(nodes));
    }
  }
  threads.joinAll();
  if (deadlockWatch.joinable()) deadlockWatch.join();
  channel.drain(accumulate);
  for (int id = 0; id < processors; ++id) {
    reports[id].node = nodes[id]->stats();
    for (int f = 0; f < node::kFaces; ++f)
      reports[id].outgoing[f] = interconnect.outgoingStats(id, node::Face(f));
  }
  MachineRun run;
  run.processors = std::move(reports);
  run.deadlock = std::move(deadlock);
  return run;
}

template class ThreadedMachine<float>;
template class ThreadedMachine<double>;

}  // namespace raycube::host
