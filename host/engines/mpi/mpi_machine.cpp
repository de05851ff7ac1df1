#include "host/engines/mpi/mpi_machine.h"

#include <sys/resource.h>

#include <chrono>
#include <optional>
#include <stdexcept>
#include <thread>

#include "host/engines/machine_wire.h"
#include "host/engines/stall_watch.h"
#include "host/machine/deadlock.h"
#include "host/util/clock.h"
#include "node/scheduling.h"

namespace raycube::host {

using queues::Packet;

std::vector<int> ranksOfProcessors(int processors, int ranks) {
  const int workers = std::min(ranks - 1, processors);
  std::vector<int> rankOf;
  for (int p = 0; p < processors; ++p) rankOf.push_back(1 + int((long long)p * workers / processors));
  return rankOf;
}

std::uint64_t peakResidentBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return std::uint64_t(usage.ru_maxrss) * 1024;
}

namespace {

// The host's side of one render: what has come back from the ranks so far.
class HostInbox {
 public:
  HostInbox(int ranks, int processors, const EngineHooks& hooks)
      : hooks_(hooks),
        evaluated_(std::size_t(processors), 0),
        stepsWorked_(std::size_t(processors), 0),
        lockedOn_(std::size_t(processors), -1),
        lockedRays_(std::size_t(processors), 0),
        results_(std::size_t(ranks)) {}

  void onPacket(int from, Packet kind, std::span<const char> bytes) {
    switch (kind) {
      case Packet::Ready:
        ++ready_;
        break;
      case Packet::Contributions:
        queues::forEachEntry<core::Contribution>(bytes,
                                                 [&](const core::Contribution& c) { hooks_.host->add(c); });
        break;
      case Packet::Progress:
        queues::forEachEntry<queues::ProcessorProgress>(bytes, [&](const queues::ProcessorProgress& p) {
          evaluated_.at(p.processor) = p.segmentsEvaluated;
          stepsWorked_.at(p.processor) = p.stepsWorked;
          lockedOn_.at(p.processor) = p.lockedOn;
          lockedRays_.at(p.processor) = p.lockedRays;
        });
        progressed_ = true;
        break;
      case Packet::Results:
        results_[from] = decodeResults(bytes);
        ++finished_;
        break;
      default:
        throw std::runtime_error("the host got an unexpected packet from rank " + std::to_string(from));
    }
  }
  void reportProgress() {
    if (!progressed_ || !hooks_.progress) return;
    hooks_.progress(evaluated_);
    progressed_ = false;
  }
  // --fifo-full lock: a deadlock, proved from what the ranks last said of their processors' locks.
  std::optional<Deadlock> deadlock(DeadlockProof& proof, const node::RegionMap& regions,
                                   std::size_t capacity) const {
    const std::vector<int> cycle = proof.look(lockedOn_, stepsWorked_, Clock::now());
    for (int p : cycle)
      if (lockedRays_[std::size_t(p)] < capacity) return std::nullopt;
    if (cycle.empty()) return std::nullopt;
    return deadlockOf(cycle, regions,
                      [&](int from, int) { return std::size_t(lockedRays_[std::size_t(from)]); });
  }
  int ready() const { return ready_; }
  int finished() const { return finished_; }
  std::vector<std::optional<RankResults>>& results() { return results_; }

 private:
  const EngineHooks& hooks_;
  int ready_ = 0, finished_ = 0;
  bool progressed_ = false;
  std::vector<std::uint64_t> evaluated_;  // per processor: ray segments (the progress line)
  std::vector<std::uint64_t> stepsWorked_;
  std::vector<int> lockedOn_;
  std::vector<std::uint64_t> lockedRays_;
  std::vector<std::optional<RankResults>> results_;
};

// Polls MPI until done() holds, calling each() every pass; the host thread naps when nothing arrives (it
// shares the cores). With a watch, the host's side of the watchdog (host/engines/stall_watch.h): no packet
// from any rank for a whole period ends the job (every rank reports its processors' progress while they
// move).
template <class Done, class Each>
void pumpUntil(queues::MpiLink& link, HostInbox& inbox, Done&& done, Each&& each, StallWatch* watch) {
  const queues::MpiLink::OnPacket handle = [&](int from, Packet kind, std::span<const char> bytes) {
    inbox.onPacket(from, kind, bytes);
  };
  std::uint64_t packets = 0;
  while (!done()) {
    const std::size_t n = link.poll(handle);
    packets += n;
    link.progressSends();
    inbox.reportProgress();
    each();
    if (n == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
    if (watch && watch->stalled([&](std::size_t) { return packets; }))
      link.abort(watch->headline() +
                 "; no rank has sent anything all that time (a ray or the termination "
                 "token lost, or a rank gone)");
  }
}

}  // namespace

template <class Real>
MachineRun MpiMachine<Real>::run(const node::MachineContext& context, std::vector<node::NodeSetup> setups,
                                 const EngineHooks& hooks) {
  const int ranks = link_.size();
  const int processors = int(setups.size());
  link_.setJob(link_.job() + 1);
  const queues::MpiTraffic before = link_.traffic();
  JobSettings settings;
  settings.precision = core::kPrecisionOf<Real>;
  settings.queueCapacity = queueCapacity_;
  settings.rayBatch = rayBatch_;
  settings.jitterSeed = jitterSeed_;
  settings.stallPeriodMs = stallPeriod_.count();
  settings.stallAStep = stallAStep_;
  settings.loseTheToken = loseTheToken_;
  settings.rankOf = ranksOfProcessors(processors, ranks);
  // 3.2 step 2: each rank receives the context and the setups of its own processors; the host keeps no
  // copy of a setup once it has left.
  std::uint64_t jobBytes = 0;
  for (int r = 1; r < ranks; ++r) {
    std::vector<node::NodeSetup> mine;
    for (int p = 0; p < processors; ++p)
      if (settings.rankOf[p] == r) mine.push_back(std::move(setups[p]));
    std::vector<char> job = encodeJob(settings, context, mine);
    jobBytes += job.size();
    link_.post(r, Packet::Job, std::move(job));
  }
  HostInbox inbox(ranks, processors, hooks);
  pumpUntil(
      link_, inbox, [&] { return inbox.ready() == ranks - 1; }, [] {}, nullptr);
  if (hooks.synthesisStarts) hooks.synthesisStarts();
  for (int r = 1; r < ranks; ++r) link_.post(r, Packet::Start, {});
  // --fifo-full lock: a deadlock proved stops every rank's processors as termination would (3.6's
  // announcement), and is the run's result.
  const auto start = Clock::now();
  std::optional<Deadlock> deadlock;
  DeadlockProof proof(
      std::chrono::duration_cast<std::chrono::milliseconds>(node::scheduling::kDeadlockQuiet));
  auto nextLook = start;
  auto lookForDeadlock = [&] {
    if (context.fifoFull != node::FifoFull::Lock || deadlock || Clock::now() < nextLook) return;
    nextLook = Clock::now() + node::scheduling::kDeadlockPoll;
    deadlock = inbox.deadlock(proof, context.regions, queueCapacity_);
    if (!deadlock) return;
    deadlock->wallSeconds = secondsSince(start);
    for (int r = 1; r < ranks; ++r) link_.post(r, Packet::Terminate, {});
  };
  StallWatch watch(1, 2 * stallPeriod_);  // twice: a rank's own watch, naming a stuck processor, speaks first
  pumpUntil(
      link_, inbox, [&] { return inbox.finished() == ranks - 1; }, lookForDeadlock, &watch);
  link_.flushSends();

  MachineRun run;
  run.processors.resize(std::size_t(processors));
  MpiRun distributed;
  distributed.rayBatch = rayBatch_;
  const queues::MpiTraffic& after = link_.traffic();
  RankReport host;
  host.jobBytes = jobBytes;
  host.peakRssBytes = peakResidentBytes();
  host.messagesSent = after.messagesSent - before.messagesSent;
  host.bytesSent = after.bytesSent - before.bytesSent;
  host.messagesReceived = after.messagesReceived - before.messagesReceived;
  host.bytesReceived = after.bytesReceived - before.bytesReceived;
  distributed.ranks.push_back(host);
  for (int r = 1; r < ranks; ++r) {
    RankResults& results = *inbox.results()[r];
    for (const ProcessorReport& p : results.processors) run.processors.at(std::size_t(p.node.id)) = p;
    distributed.ranks.push_back(results.rank);
  }
  run.mpi = std::move(distributed);
  run.deadlock = std::move(deadlock);
  return run;
}

template class MpiMachine<float>;
template class MpiMachine<double>;

}  // namespace raycube::host
