#pragma once
// The machine's interconnect in one address space: a bounded lock-free FIFO per directed adjacency (capacity
// --queue-capacity, 128 as on the iPSC), a doorbell per processor, a token mailbox per processor on the
// ring, and a block channel per processor to the host.
#include <atomic>
#include <memory>
#include <vector>

#include "node/region_map.h"
#include "node/transport.h"
#include "queues/doorbell.h"
#include "queues/host_channel.h"
#include "queues/spsc_queue.h"

namespace raycube::host {

using ContributionChannel = queues::HostChannel<core::Contribution, 256>;
// Blocks a processor may have in flight to the host before it waits: enough for the host's batching pause.
inline constexpr std::size_t kContributionBlocksPerProcessor = 32;

// Real: the precision of the rays the FIFOs carry (node::BasicRayMessage<Real>).
template <class Real>
class SharedMemoryMachine {
 public:
  using RayQueue = queues::SpscQueue<node::BasicRayMessage<Real>, queues::Accounting::kOn>;

  SharedMemoryMachine(const node::RegionMap& regions, std::size_t queueCapacity);
  SharedMemoryMachine(const SharedMemoryMachine&) = delete;
  SharedMemoryMachine& operator=(const SharedMemoryMachine&) = delete;
  ~SharedMemoryMachine();

  node::BasicTransport<Real>& endpoint(int processor);
  ContributionChannel& hostChannel() { return channel_; }
  bool terminated() const { return terminated_.load(std::memory_order_acquire); }
  // Saturation of the FIFOs a processor sends into, summed per face of the processor.
  queues::QueueStats outgoingStats(int processor, node::Face face) const;

 private:
  class Endpoint;
  struct Mailbox {
    std::atomic<bool> full{false};
    node::Token token;
  };
  RayQueue* queue(int from, int to) const;

  const node::RegionMap& regions_;
  std::vector<std::unique_ptr<queues::Doorbell>> bells_;
  // outgoing_[p][k]: from processor p to its k-th neighbour
  std::vector<std::vector<std::unique_ptr<RayQueue>>> outgoing_;
  std::vector<std::unique_ptr<Mailbox>> mailboxes_;
  ContributionChannel channel_;
  std::atomic<bool> terminated_{false};
  std::vector<std::unique_ptr<Endpoint>> endpoints_;
};

}  // namespace raycube::host
