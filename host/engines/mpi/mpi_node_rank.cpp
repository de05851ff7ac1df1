// Ranks 1..N-1 of the MPI machine: each render, build this rank's processors from the setups the host
// sent, run them on threads over the rank's interconnect, and send back their reports. The calling thread
// is the rank's communication task: the only one that calls MPI.
#include <atomic>
#include <chrono>
#include <latch>
#include <mutex>
#include <optional>
#include <thread>

#include "host/engines/machine_wire.h"
#include "host/engines/mpi/mpi_machine.h"
#include "host/engines/node_thread.h"
#include "host/engines/processor_thread.h"
#include "host/engines/stall_watch.h"
#include "queues/interconnects/jitter_transport.h"
#include "queues/interconnects/mpi_interconnect.h"
#include "queues/interconnects/step_stalling_transport.h"
#include "queues/interconnects/token_losing_transport.h"

namespace raycube::host {

using queues::Packet;

namespace {

// The first failure of a processor's thread, for the communication task to report.
class Failure {
 public:
  void record(const std::string& cause) {
    std::lock_guard lock(mutex_);
    if (!failed_.exchange(true)) cause_ = cause;
  }
  bool failed() const { return failed_.load(); }
  std::string cause() const {
    std::lock_guard lock(mutex_);
    return cause_;
  }

 private:
  mutable std::mutex mutex_;
  std::atomic<bool> failed_{false};
  std::string cause_;
};

template <class Body>
void guarded(Failure& failure, int id, Body&& body) {
  try {
    body();
  } catch (const std::exception& e) {
    failure.record("processor " + std::to_string(id) + ": " + e.what());
  }
}

// The transports this rank's processors talk through: its interconnect's endpoints, each behind a jitter
// when the job asks for one (tests of the termination protocol).
template <class Real>
struct LocalTransports {
  std::vector<std::unique_ptr<queues::JitterTransport<Real>>> jitters;
  std::unique_ptr<queues::StepStallingTransport<Real>> stalling;                 // JobSettings::stallAStep
  std::vector<std::unique_ptr<queues::TokenLosingTransport<Real>>> tokenLosing;  // JobSettings::loseTheToken
  std::vector<node::BasicTransport<Real>*> transports;
  std::vector<int> ids;
  std::uint64_t objectsHeld = 0;
};

template <class Real>
LocalTransports<Real> localTransports(const MachineJob& job, queues::MpiInterconnect<Real>& net) {
  LocalTransports<Real> local;
  for (const node::NodeSetup& s : job.setups) {
    local.ids.push_back(s.id);
    local.objectsHeld += s.database->size();
    local.transports.push_back(&net.endpoint(s.id));
    if (job.settings.jitterSeed > 0) {
      local.jitters.push_back(std::make_unique<queues::JitterTransport<Real>>(
          *local.transports.back(), job.settings.jitterSeed * 7919u + unsigned(s.id)));
      local.transports.back() = local.jitters.back().get();
    }
    if (job.settings.loseTheToken) {
      local.tokenLosing.push_back(
          std::make_unique<queues::TokenLosingTransport<Real>>(*local.transports.back()));
      local.transports.back() = local.tokenLosing.back().get();
    }
    if (job.settings.stallAStep && s.id + 1 == int(job.settings.rankOf.size())) {
      local.stalling = std::make_unique<queues::StepStallingTransport<Real>>(*local.transports.back());
      local.transports.back() = local.stalling.get();
    }
  }
  return local;
}

// What the host hears of a processor: its progress and, under the paper's flow control, its lock. Steps
// are read before the lock, as the threads engine's deadlock watch reads them.
template <class Real>
queues::ProcessorProgress progressOf(const queues::MpiInterconnect<Real>& net,
                                     const node::LogicalProcessor<Real>& processor, int id) {
  queues::ProcessorProgress p;
  p.processor = std::uint32_t(id);
  p.stepsWorked = processor.stepsWorked();
  p.segmentsEvaluated = processor.segmentsEvaluated();
  p.lockedOn = processor.lockedOn();
  if (p.lockedOn >= 0) p.lockedRays = net.raysToward(id, p.lockedOn);
  return p;
}

// The communication task's view of the processors' threads: when they have stopped, their progress, the
// host's start and quit, and their first failure.
template <class Real>
typename queues::MpiInterconnect<Real>::ServeHooks serveHooks(
    const queues::MpiInterconnect<Real>& net, const std::atomic<std::size_t>& running,
    const std::vector<std::unique_ptr<node::LogicalProcessor<Real>>>& nodes, const std::vector<int>& ids,
    std::latch& synthesis, const Failure& failure, StallWatch& stallWatch) {
  typename queues::MpiInterconnect<Real>::ServeHooks hooks;
  hooks.stopped = [&] { return running.load() == 0; };
  hooks.progress = [&] {
    std::vector<queues::ProcessorProgress> progress;
    for (std::size_t k = 0; k < nodes.size(); ++k)
      if (nodes[k]) progress.push_back(progressOf(net, *nodes[k], ids[k]));
    return progress;
  };
  hooks.other = [&](int from, Packet kind, std::span<const char>) {
    if (from == 0 && kind == Packet::Start) return synthesis.count_down();
    if (from == 0 && kind == Packet::Quit)
      throw std::runtime_error("the host (rank 0) stopped during the render");
  };
  // The rank's side of the watchdog (host/engines/stall_watch.h): a processor of this rank inside one step
  // while none of them moved for a whole period ends the job, naming it (link.abort).
  hooks.check = [&] {
    if (failure.failed()) throw std::runtime_error(failure.cause());
    if (!stallWatch.stalled([&](std::size_t k) { return nodes[k] ? nodes[k]->stepsWorked() : 0; })) return;
    std::string busy;
    for (std::size_t k = 0; k < nodes.size(); ++k)
      if (nodes[k] && nodes[k]->stepping()) busy += (busy.empty() ? "" : ", ") + std::to_string(ids[k]);
    if (!busy.empty())
      throw std::runtime_error(stallWatch.headline() + "; processor " + busy +
                               " has been inside one step all that time (a walk that does not end)");
  };
  return hooks;
}

// What the rank sends back: its processors' reports, and what it held and sent (the job and the results
// messages counted in).
template <class Real>
RankResults rankResults(const queues::MpiInterconnect<Real>& net, const queues::MpiLink& link,
                        const queues::MpiTraffic& before, std::uint64_t jobBytes,
                        const LocalTransports<Real>& local,
                        const std::vector<std::unique_ptr<node::LogicalProcessor<Real>>>& nodes,
                        std::vector<ProcessorReport>& reports) {
  RankResults results;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    reports[k].node = nodes[k]->stats();
    for (int f = 0; f < node::kFaces; ++f)
      reports[k].outgoing[f] = net.outgoingStats(local.ids[k], node::Face(f));
    results.processors.push_back(reports[k]);
  }
  const queues::MpiTraffic& after = link.traffic();
  RankReport& r = results.rank;
  r.rank = link.rank();
  r.processors = int(nodes.size());
  r.objects = local.objectsHeld;
  r.jobBytes = jobBytes;
  r.peakRssBytes = peakResidentBytes();
  r.messagesSent = after.messagesSent - before.messagesSent + 1;  // with the results
  r.bytesSent = after.bytesSent - before.bytesSent;
  r.messagesReceived = after.messagesReceived - before.messagesReceived + 1;  // with the job
  r.bytesReceived = after.bytesReceived - before.bytesReceived + jobBytes;
  r.rayMessages = net.rayTraffic().rayMessages;
  r.raysSent = net.rayTraffic().raysSent;
  return results;
}

template <class Real>
void runJob(MachineJob job, queues::MpiLink& link, std::uint64_t jobBytes) {
  const queues::MpiTraffic before = link.traffic();
  queues::MpiInterconnect<Real> net(
      job.context.regions,
      queues::MpiWiring{job.settings.rankOf, job.settings.queueCapacity, job.settings.rayBatch}, link);
  const std::size_t local = job.setups.size();
  LocalTransports<Real> transports = localTransports(job, net);
  const std::vector<int>& ids = transports.ids;
  std::vector<std::unique_ptr<node::LogicalProcessor<Real>>> nodes(local);
  std::vector<ProcessorReport> reports(local);
  Failure failure;
  std::atomic<std::size_t> running(local);
  std::latch subdivided{std::ptrdiff_t(local)};
  std::latch synthesis(1);
  ProcessorThreads threads;
  for (std::size_t k = 0; k < local; ++k)
    threads.start([&, k] {
      const int id = ids[k];
      guarded(failure, id, [&] {
        nodes[k] = std::make_unique<node::LogicalProcessor<Real>>(job.context, std::move(job.setups[k]),
                                                                  *transports.transports[k]);
      });
      subdivided.count_down();
      synthesis.wait();
      if (nodes[k]) guarded(failure, id, [&] { driveNodeThread(*nodes[k], net, id, reports[k]); });
      running.fetch_sub(1);
    });
  try {
    subdivided.wait();
    if (failure.failed()) throw std::runtime_error(failure.cause());
    link.post(0, Packet::Ready, {});
    StallWatch stallWatch(local, std::chrono::milliseconds(job.settings.stallPeriodMs));
    net.serve(serveHooks<Real>(net, running, nodes, ids, synthesis, failure, stallWatch));
  } catch (const std::exception& e) {
    link.abort(e.what());  // threads may be waiting for rays that will never come: end the job here
  }
  threads.joinAll();

  link.post(0, Packet::Results,
            encodeResults(rankResults(net, link, before, jobBytes, transports, nodes, reports)));
  link.flushSends();
}

}  // namespace

int serveMachineJobs(queues::MpiLink& link) {
  for (;;) {
    std::vector<char> job;
    std::optional<int> quit;
    const queues::MpiLink::OnPacket handle = [&](int from, Packet kind, std::span<const char> bytes) {
      if (from == 0 && kind == Packet::Job) job.assign(bytes.begin(), bytes.end());
      if (from == 0 && kind == Packet::Quit) quit = queues::packetValue<int>(bytes);
    };
    while (job.empty() && !quit)
      if (link.poll(handle, 1) == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
    if (quit) return *quit;
    MachineJob decoded = decodeJob(job);
    core::withPrecision(decoded.settings.precision,
                        [&]<class Real>() { runJob<Real>(std::move(decoded), link, job.size()); });
  }
}

}  // namespace raycube::host
