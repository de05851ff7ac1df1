#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "queues/doorbell.h"
#include "queues/spsc_queue.h"

namespace raycube::queues {

// Pixel contributions from every node to the host. One SPSC queue of blocks per node (rather than one
// MPSC queue) keeps the nodes from contending with each other; the host scans them all.
// As in Priol & Bouatouch, a node fills a block of contributions and ships it when full or when idle.
template <class Contribution, std::size_t kBlockSize = 64>
class HostChannel {
 public:
  static constexpr std::size_t kDefaultBlocksPerSender = 8;

  struct Block {
    std::uint32_t count = 0;
    std::array<Contribution, kBlockSize> items{};
    std::span<const Contribution> contributions() const { return {items.data(), count}; }
  };
  using Queue = SpscQueue<Block>;

  // Node side: one sender per node, used by that node's thread only.
  class Sender {
   public:
    Sender(Sender&&) noexcept = default;
    Sender& operator=(Sender&&) noexcept = default;
    Sender(const Sender&) = delete;  // two senders on one queue would break single-producer
    Sender& operator=(const Sender&) = delete;

    void send(const Contribution& contribution) {
      block_.items[block_.count++] = contribution;
      if (block_.count == kBlockSize) flush();
    }
    // Ships a partial block; call when the node goes idle. Waits (sleeping on the node's bell) if full.
    void flush() {
      if (block_.count == 0) return;
      queue_->push(block_);
      block_.count = 0;
    }
    std::size_t unsent() const { return block_.count; }

   private:
    friend class HostChannel;
    explicit Sender(Queue* queue) : queue_(queue) {}
    Queue* queue_;
    Block block_;
  };

  // senderBells[i], if given and not null, is node i's doorbell: the host rings it after draining node i's
  // queue, so that node may sleep while its queue is full.
  explicit HostChannel(std::size_t senders, std::size_t blocksPerSender = kDefaultBlocksPerSender,
                       std::span<Doorbell* const> senderBells = {}) {
    if (!senderBells.empty() && senderBells.size() != senders) {
      throw std::invalid_argument("HostChannel: got " + std::to_string(senderBells.size()) +
                                  " sender doorbells for " + std::to_string(senders) + " senders");
    }
    queues_.reserve(senders);
    for (std::size_t i = 0; i < senders; ++i) {
      queues_.push_back(std::make_unique<Queue>(SpscOptions{
          .capacity = blocksPerSender,
          .consumerBell = &hostBell_,
          .producerBell = senderBells.empty() ? nullptr : senderBells[i],
      }));
    }
  }

  Sender sender(std::size_t node) { return Sender(queues_.at(node).get()); }

  // ---- Host side: one thread only.

  // Hands every contribution queued right now to onContribution; returns how many.
  template <class OnContribution>
  std::size_t drain(OnContribution&& onContribution) {
    std::size_t delivered = 0;
    for (auto& queue : queues_) {
      while (queue->tryPop(scratch_)) {
        for (const Contribution& c : scratch_.contributions()) onContribution(c);
        delivered += scratch_.count;
      }
    }
    return delivered;
  }

  bool anyPending() const {
    for (const auto& queue : queues_) {
      if (queue->hasMessage()) return true;
    }
    return false;
  }

  // Rung by every sender after each block; the host sleeps on it (see waitUntil), and may also be rung by
  // whoever else needs to wake the host, e.g. termination detection.
  Doorbell& doorbell() { return hostBell_; }

 private:
  Doorbell hostBell_;
  std::vector<std::unique_ptr<Queue>> queues_;
  Block scratch_;
};

}  // namespace raycube::queues
