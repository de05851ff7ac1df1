#pragma once
// The machine's interconnect across MPI ranks (one rank's share of it). Processors on this rank talk
// through the shared-memory FIFOs; a ray for a processor on another rank goes into a FIFO towards this
// rank's communication task, which batches the rays for one rank into one MPI message (rayBatch rays at
// most). The paper's bounded FIFOs (3.5.2) hold across ranks with credits: a processor may have at most
// `capacity` rays in flight towards a neighbour, and the neighbour's rank returns a credit for each ray
// the neighbour has taken. The token (3.6), the announcement of termination and the contribution blocks for
// the host (3.4) travel as packets too. One thread, the communication task (serve), calls MPI; the
// processors' threads only touch lock-free queues and atomics, and sleep on their doorbells.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "node/region_map.h"
#include "node/scheduling.h"
#include "node/transport.h"
#include "queues/doorbell.h"
#include "queues/handoff_slot.h"
#include "queues/host_channel.h"
#include "queues/interconnects/mpi_link.h"
#include "queues/spsc_queue.h"
#include "queues/wait.h"

namespace raycube::queues {

struct MpiWiring {
  std::vector<int> rankOf;  // per processor
  std::size_t capacity = kPaperFifoCapacity;
  std::size_t rayBatch = 16;
};

// What this rank's communication task sent: MPI messages with rays, and the rays in them.
struct MpiRayTraffic {
  std::uint64_t rayMessages = 0, raysSent = 0;
};

template <class Real>
class MpiInterconnect {
 public:
  using Message = node::BasicRayMessage<Real>;
  using RayQueue = SpscQueue<Message, Accounting::kOn>;

  MpiInterconnect(const node::RegionMap& regions, MpiWiring wiring, MpiLink& link);
  MpiInterconnect(const MpiInterconnect&) = delete;
  MpiInterconnect& operator=(const MpiInterconnect&) = delete;
  ~MpiInterconnect();

  bool local(int processor) const { return wiring_.rankOf[processor] == link_.rank(); }
  node::BasicTransport<Real>& endpoint(int processor);  // a processor of this rank
  template <class Ready>
  void waitFor(int processor, Ready&& ready) {
    const auto policy = node::scheduling::kNodeWait;
    waitUntil(*bells_[processor], ready, WaitPolicy{policy.spins, policy.yields});
  }
  void ringNeighbours(int) {}  // its FIFOs ring as they are pushed
  bool terminated() const { return terminated_.load(std::memory_order_acquire); }
  QueueStats outgoingStats(int processor, node::Face face) const;
  // Rays a local processor has sent towards its neighbour `to` and the neighbour has not taken: in its FIFO
  // (a neighbour on this rank) or anywhere on the way (another rank's: the credits it lacks). The paper's
  // flow control locks the sender when this reaches the capacity.
  std::size_t raysToward(int from, int to) const;

  struct ServeHooks {
    std::function<bool()> stopped;                             // every processor of this rank has returned
    std::function<std::vector<ProcessorProgress>()> progress;  // this rank's processors, for the host
    MpiLink::OnPacket other;      // packets that are not the interconnect's (Start, Quit)
    std::function<void()> check;  // every pass: throws if a processor's thread has failed
  };
  // The communication task, on the calling thread: runs until termination is known here and every local
  // processor has stopped, then ships the last contributions. The host (rank 0) must follow with
  // nothing from this rank but its results.
  void serve(const ServeHooks& hooks);
  const MpiRayTraffic& rayTraffic() const { return rayTraffic_; }
  // Per edge to or from another rank: credits, rays waiting, rays taken and credits returned (a hang's
  // diagnosis). Reads the communication task's counters: call it from that thread, or once it has stopped.
  std::string describe() const;

 private:
  class Endpoint;
  struct RemoteOut;
  struct RemoteIn;
  using TokenSlot = HandoffSlot<node::Token>;
  struct OutgoingToken {
    int to = 0;
    node::Token token;
  };
  // The communication task's doorbell: processors ring it when they hand it something; it also wakes up
  // on its own to look for MPI messages, which ring nothing.
  class TaskBell {
   public:
    void ring();
    void sleepFor(std::chrono::microseconds timeout);

   private:
    std::mutex mutex_;
    std::condition_variable wake_;
    std::atomic<bool> sleeping_{false};
    std::atomic<std::uint64_t> rings_{0};
  };

  void onPacket(int from, Packet kind, std::span<const char> bytes, const ServeHooks& hooks);
  void deliverToken(int to, const node::Token& token);
  void terminateHere();
  bool collectRays(bool& anyGrew, std::vector<char>& grew);
  void sendRays(int rank);
  bool returnCredits(bool flushAll);
  bool forwardToken();
  bool forwardContributions(bool flush);
  bool announceTermination();
  bool raysInFlight() const;
  // The processors' progress to the host, at most every kProgressPeriod and only when it changed.
  void reportProgress(const ServeHooks& hooks, std::chrono::steady_clock::time_point& next,
                      std::vector<ProcessorProgress>& reported);
  // After a pass with nothing to do: yield, then nap longer the more passes found nothing.
  void waitIdle(int idlePasses);

  const node::RegionMap& regions_;
  MpiWiring wiring_;
  MpiLink& link_;
  std::size_t creditBatch_;
  std::vector<std::unique_ptr<Doorbell>> bells_;        // per processor (null for other ranks')
  std::vector<std::unique_ptr<TokenSlot>> tokenSlots_;  // per processor (null for other ranks')
  // Per local processor and neighbour slot: its FIFO towards the neighbour, and its credits when the
  // neighbour is on another rank (null otherwise).
  std::vector<std::vector<RayQueue*>> outgoing_;
  std::vector<std::vector<std::atomic<std::int64_t>*>> credits_;
  std::vector<std::vector<RayQueue*>> incoming_;  // per local processor, per neighbour slot
  std::vector<std::unique_ptr<RayQueue>> localFifos_;
  std::vector<std::unique_ptr<RemoteOut>> remoteOut_;
  std::map<std::pair<int, int>, std::unique_ptr<RemoteIn>> remoteIn_;  // (from, to)
  std::map<std::pair<int, int>, RemoteOut*> remoteOutByEdge_;
  std::vector<std::vector<char>> batches_;  // per rank: rays waiting for an MPI message
  std::vector<int> batchRays_;
  std::vector<Message> scratch_;                  // rays on their way from a FIFO into a batch
  std::vector<std::vector<char>> creditPackets_;  // per rank: credits waiting for an MPI message
  std::atomic<bool> terminated_{false};
  std::atomic<bool> announced_{false};
  HandoffSlot<OutgoingToken> tokenOut_;  // from a local processor to the communication task
  std::vector<int> localIds_;
  HostChannel<core::Contribution, node::scheduling::kContributionBlock> contributions_;
  std::vector<core::Contribution> contributionBlock_;
  TaskBell taskBell_;
  MpiRayTraffic rayTraffic_;
  std::vector<std::unique_ptr<Endpoint>> endpoints_;  // per processor (null for other ranks')
};

}  // namespace raycube::queues
