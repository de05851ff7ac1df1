#pragma once

#include <algorithm>
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

// Contributions an engine gathers before shipping them across an address space to the host at once (a pipe
// to the parent process, an MPI message): large enough that a block costs little per contribution.
inline constexpr std::size_t kContributionsPerShipment = 4096;

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
      Block& block = open();
      block.items[block.count++] = contribution;
      if (block.count == kBlockSize) flush();
    }
    // Ships a partial block; call when the node goes idle. Waits (sleeping on the node's bell) if full.
    void flush() {
      if (unsent() == 0) return;
      if (inSpare_) {
        // Only the contributions: a node going idle ships the few it has, and 8 x 8's processors, with two
        // blocks each, often find the queue full (copying whole 8 KB blocks there cost instructions for
        // nothing).
        Block& slot = queue_->claimWaiting();
        slot.count = spare_.count;
        std::copy_n(spare_.items.begin(), spare_.count, slot.items.begin());
      }
      queue_->publish();
      claimed_ = nullptr;
      inSpare_ = false;
    }
    std::size_t unsent() const { return inSpare_ ? spare_.count : claimed_ != nullptr ? claimed_->count : 0; }

   private:
    friend class HostChannel;
    explicit Sender(Queue* queue) : queue_(queue) {}
    // The block being filled: a slot of the queue, claimed and filled in place (a block is 8 KB: copying
    // it in and out cost millions of instructions a run), or, while the queue is full, the spare,
    // copied in when it ships.
    Block& open() {
      if (inSpare_) return spare_;
      if (claimed_ != nullptr) return *claimed_;
      claimed_ = queue_->claim();
      inSpare_ = claimed_ == nullptr;
      Block& block = inSpare_ ? spare_ : *claimed_;
      block.count = 0;
      return block;
    }

    Queue* queue_;
    Block* claimed_ = nullptr;
    bool inSpare_ = false;
    Block spare_;
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
      while (const Block* block = queue->front()) {  // read in place
        for (const Contribution& c : block->contributions()) onContribution(c);
        delivered += block->count;
        queue->release();
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
};

}  // namespace raycube::queues
