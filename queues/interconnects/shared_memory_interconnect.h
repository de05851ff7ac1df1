#pragma once
// The machine's interconnect in one address space (Priol & Bouatouch 3.5): a bounded lock-free FIFO per
// directed adjacency (capacity --queue-capacity: 512 rays, node::scheduling::kThreadsFifoRays), a doorbell
// per processor (rung once per step of a neighbour that sent it rays: ringNeighbours), a token slot per
// processor on the ring (3.6), a block channel per processor to the host (3.4), and the count of rays waiting
// for room machine-wide, which holds primary rays back (scheduling::kMachineBacklogLimit). Each processor
// talks to it through its endpoint (the node's transport); the threads' driver waits on the processor's
// doorbell, and the host drains the channel.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "node/region_map.h"
#include "node/scheduling.h"
#include "node/transport.h"
#include "queues/cache_line.h"
#include "queues/doorbell.h"
#include "queues/handoff_slot.h"
#include "queues/host_channel.h"
#include "queues/spsc_queue.h"
#include "queues/wait.h"

namespace raycube::queues {

using ContributionChannel = HostChannel<core::Contribution, node::scheduling::kContributionBlock>;

// Real: the precision of the rays the FIFOs carry (node::BasicRayMessage<Real>).
template <class Real>
class SharedMemoryInterconnect {
 public:
  using RayQueue = SpscQueue<node::BasicRayMessage<Real>, Accounting::kOn>;

  // backlogLimit: waiting rays from which primaries are held back (scheduling::kMachineBacklogLimit).
  SharedMemoryInterconnect(const node::RegionMap& regions, std::size_t queueCapacity,
                           std::size_t backlogLimit = node::scheduling::kMachineBacklogLimit);
  SharedMemoryInterconnect(const SharedMemoryInterconnect&) = delete;
  SharedMemoryInterconnect& operator=(const SharedMemoryInterconnect&) = delete;
  ~SharedMemoryInterconnect();

  node::BasicTransport<Real>& endpoint(int processor);
  // The driver of a processor's thread: returns once ready() holds (spin, yield, then sleep on its bell).
  template <class Ready>
  void waitFor(int processor, Ready&& ready) {
    const auto policy = node::scheduling::kNodeWait;
    waitUntil(*bells_[processor], ready, WaitPolicy{policy.spins, policy.yields});
  }
  // The driver, after each step of the processor: wakes those of its neighbours it sent rays to during the
  // step that sleep. Once per step, not per ray: with the fence on the ringer's side (Doorbell's kSymmetric),
  // a ring per ray cost as much as it saved, and the sleepers' membarriers (kAsymmetric) cost the SPD's
  // small scenes more at 8 x 8 than a fence per ring.
  void ringNeighbours(int processor);
  ContributionChannel& hostChannel() { return channel_; }
  // Rays waiting in every processor's overflow lists, as they report them (BasicTransport::countWaiting).
  std::int64_t waitingRays() const {
    return std::int64_t(backPressure_.load(std::memory_order_relaxed) >> 1);
  }
  bool terminated() const { return terminated_.load(std::memory_order_acquire); }
  // The host's watchdog, on a machine that stalled: every processor's next step returns Terminated.
  void stop();
  // Rays in the FIFO from processor `from` to its neighbour `to`: a snapshot any thread may take.
  std::size_t raysIn(int from, int to) const { return queue(from, to)->size(); }
  // Saturation of the FIFOs a processor sends into, summed per face of the processor.
  QueueStats outgoingStats(int processor, node::Face face) const;

 private:
  class Endpoint;
  using TokenSlot = HandoffSlot<node::Token>;
  RayQueue* queue(int from, int to) const;
  void countWaiting(std::ptrdiff_t change);
  bool primariesHeld() const;

  const node::RegionMap& regions_;
  const std::int64_t backlogLimit_, backlogRelease_;
  std::vector<std::unique_ptr<Doorbell>> bells_;
  SlotStorage<node::BasicRayMessage<Real>> fifoSlots_;  // every FIFO's, in one block (see SlotStorage)
  // outgoing_[p][k]: from processor p to its k-th neighbour
  std::vector<std::vector<std::unique_ptr<RayQueue>>> outgoing_;
  std::vector<std::unique_ptr<TokenSlot>> tokenSlots_;
  ContributionChannel channel_;
  std::atomic<bool> terminated_{false};
  // Rays waiting in the overflow lists, shifted left once, and whether primaries are held (the low bit).
  alignas(kCacheLine) std::atomic<std::uint64_t> backPressure_{0};
  std::vector<std::unique_ptr<Endpoint>> endpoints_;
};

}  // namespace raycube::queues
