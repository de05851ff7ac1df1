#pragma once

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "queues/cache_line.h"
#include "queues/doorbell.h"
#include "queues/queue_stats.h"
#include "queues/wait.h"

namespace raycube::queues {

// Priol & Bouatouch 3.7: each face of a processor buffers 128 rays.
inline constexpr std::size_t kPaperFifoCapacity = 128;

// Compile-time, so that a queue without accounting carries no counters and no branches.
enum class Accounting { kOff, kOn };

struct SpscOptions {
  std::size_t capacity = kPaperFifoCapacity;  // any value >= 1
  Doorbell* consumerBell = nullptr;           // rung after every push; the consumer sleeps on it when empty
  Doorbell* producerBell = nullptr;           // rung after every pop; the producer sleeps on it when full
  std::uint64_t firstIndex = 0;               // tests start near 2^64 to cross the index wrap-around
  WaitPolicy wait = {};                       // used by the blocking push/pop
};

// Bounded single-producer/single-consumer FIFO of trivially copyable messages.
// Indices count messages forever (wrapping at 2^64); the slot of index i is i & mask_, with the slot
// array rounded up to a power of two so that the wrap lands on slot 0 whatever the capacity.
// Aligned to a cache line so that whatever is allocated next cannot share the producer's line.
template <class T, Accounting kAccounting = Accounting::kOff>
class alignas(kCacheLine) SpscQueue {
  static_assert(std::is_trivially_copyable_v<T> && std::is_default_constructible_v<T>,
                "SpscQueue copies messages bytewise: use a trivially copyable message type");
  static constexpr bool kCounting = kAccounting == Accounting::kOn;

 public:
  using value_type = T;

  explicit SpscQueue(std::size_t capacity = kPaperFifoCapacity)
      : SpscQueue(SpscOptions{.capacity = capacity}) {}

  explicit SpscQueue(const SpscOptions& options)
      : capacity_(checkedCapacity(options.capacity)),
        mask_(std::bit_ceil(options.capacity) - 1),
        slots_(std::make_unique<T[]>(mask_ + 1)),
        consumerBell_(options.consumerBell),
        producerBell_(options.producerBell),
        wait_(options.wait) {
    head_.store(options.firstIndex, std::memory_order_relaxed);
    tail_.store(options.firstIndex, std::memory_order_relaxed);
    tailCache_ = headCache_ = options.firstIndex;
  }

  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  // ---- Producer side: one thread only.

  bool tryPush(const T& message) { return tryPushN(std::span<const T>(&message, 1)) == 1; }

  // Pushes the longest prefix of messages that fits; returns its length.
  std::size_t tryPushN(std::span<const T> messages) {
    const std::size_t pushed = pushSome(messages);
    if constexpr (kCounting) {
      if (pushed < messages.size()) bump(producer_.refusedPushes);
    }
    return pushed;
  }

  void push(const T& message) { pushN(std::span<const T>(&message, 1)); }

  // Waits (spin, yield, then sleep on the producer bell) until every message is in.
  void pushN(std::span<const T> messages) {
    std::size_t done = pushSome(messages);
    if (done == messages.size()) return;
    const Clock::time_point start = startClock();
    if constexpr (kCounting) bump(producer_.refusedPushes);
    while (done < messages.size()) {
      waitUntil(
          producerBell_, [this] { return hasSpace(); }, wait_);
      done += pushSome(messages.subspan(done));
    }
    if constexpr (kCounting) bump(producer_.nanosBlockedFull, elapsedNanos(start));
  }

  // ---- Consumer side: one thread only.

  bool tryPop(T& out) { return tryPopN(std::span<T>(&out, 1)) == 1; }

  // Pops up to out.size() messages into out; returns how many.
  std::size_t tryPopN(std::span<T> out) {
    const std::size_t popped = popSome(out);
    if constexpr (kCounting) {
      if (popped == 0) bump(consumer_.emptyPops);
    }
    return popped;
  }

  T pop() {
    T message;
    popN(std::span<T>(&message, 1));
    return message;
  }

  // Waits (spin, yield, then sleep on the consumer bell) for at least one message; returns how many.
  std::size_t popN(std::span<T> out) {
    std::size_t popped = popSome(out);
    if (popped > 0 || out.empty()) return popped;
    const Clock::time_point start = startClock();
    if constexpr (kCounting) bump(consumer_.emptyPops);
    while (popped == 0) {
      waitUntil(
          consumerBell_, [this] { return hasMessage(); }, wait_);
      popped = popSome(out);
    }
    if constexpr (kCounting) bump(consumer_.nanosBlockedEmpty, elapsedNanos(start));
    return popped;
  }

  // ---- Either side, or an observer: snapshots that may be stale when they return.

  std::size_t size() const {
    const std::uint64_t head = head_.load(std::memory_order_acquire);
    return static_cast<std::size_t>(tail_.load(std::memory_order_acquire) - head);
  }
  bool empty() const { return size() == 0; }
  std::size_t capacity() const { return capacity_; }

  // True when the consumer could pop / the producer could push; what a waiter's predicate looks at.
  bool hasMessage() const {
    return tail_.load(std::memory_order_acquire) != head_.load(std::memory_order_relaxed);
  }
  bool hasSpace() const {
    return tail_.load(std::memory_order_relaxed) - head_.load(std::memory_order_acquire) < capacity_;
  }

  // All zero (but capacity) unless the queue was built with Accounting::kOn.
  QueueStats stats() const {
    QueueStats s;
    s.capacity = capacity_;
    if constexpr (kCounting) {
      s.pushed = read(producer_.pushed);
      s.refusedPushes = read(producer_.refusedPushes);
      s.nanosBlockedFull = read(producer_.nanosBlockedFull);
      s.highWater = read(producer_.highWater);
      s.occupancySamples = read(producer_.occupancySamples);
      s.occupancySum = read(producer_.occupancySum);
      for (std::size_t b = 0; b < kOccupancyBuckets; ++b)
        s.occupancyHistogram[b] = read(producer_.histogram[b]);
      s.popped = read(consumer_.popped);
      s.emptyPops = read(consumer_.emptyPops);
      s.nanosBlockedEmpty = read(consumer_.nanosBlockedEmpty);
    }
    return s;
  }

 private:
  using Clock = std::chrono::steady_clock;
  using Counter = std::atomic<std::uint64_t>;  // one writer; atomic only so that stats() may read it live

  struct ProducerCounters {
    Counter pushed{0}, refusedPushes{0}, nanosBlockedFull{0}, highWater{0}, occupancySamples{0},
        occupancySum{0};
    std::array<Counter, kOccupancyBuckets> histogram{};
  };
  struct ConsumerCounters {
    Counter popped{0}, emptyPops{0}, nanosBlockedEmpty{0};
  };
  struct NoCounters {};

  std::size_t pushSome(std::span<const T> messages) {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    // With accounting on, always refresh: the occupancy sample must not be a stale upper bound.
    if (kCounting || capacity_ - (tail - headCache_) < messages.size()) {
      headCache_ = head_.load(std::memory_order_acquire);
    }
    const std::size_t n = std::min<std::size_t>(messages.size(), capacity_ - (tail - headCache_));
    if (n == 0) return 0;
    for (std::size_t i = 0; i < n; ++i) slots_[(tail + i) & mask_] = messages[i];
    tail_.store(tail + n, std::memory_order_release);
    if (consumerBell_ != nullptr) consumerBell_->ring();
    if constexpr (kCounting) recordPush(n, tail + n - headCache_);
    return n;
  }

  std::size_t popSome(std::span<T> out) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (tailCache_ - head < out.size()) tailCache_ = tail_.load(std::memory_order_acquire);
    const std::size_t n = std::min<std::size_t>(out.size(), tailCache_ - head);
    if (n == 0) return 0;
    for (std::size_t i = 0; i < n; ++i) out[i] = slots_[(head + i) & mask_];
    head_.store(head + n, std::memory_order_release);
    if (producerBell_ != nullptr) producerBell_->ring();
    if constexpr (kCounting) bump(consumer_.popped, n);
    return n;
  }

  void recordPush(std::size_t n, std::uint64_t occupancy) {
    bump(producer_.pushed, n);
    bump(producer_.occupancySamples);
    bump(producer_.occupancySum, occupancy);
    bump(producer_.histogram[occupancyBucket(occupancy, capacity_)]);
    if (occupancy > read(producer_.highWater))
      producer_.highWater.store(occupancy, std::memory_order_relaxed);
  }

  static void bump(Counter& counter, std::uint64_t by = 1) {
    counter.store(counter.load(std::memory_order_relaxed) + by, std::memory_order_relaxed);
  }
  static std::uint64_t read(const Counter& counter) { return counter.load(std::memory_order_relaxed); }
  static Clock::time_point startClock() {
    if constexpr (kCounting) return Clock::now();
    return {};
  }
  static std::uint64_t elapsedNanos(Clock::time_point start) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count();
  }
  static std::size_t checkedCapacity(std::size_t capacity) {
    if (capacity == 0 || capacity > (std::size_t{1} << 40)) {
      throw std::invalid_argument("SpscQueue capacity must be between 1 and 2^40, got " +
                                  std::to_string(capacity));
    }
    return capacity;
  }

  // Read by both sides, written by neither after construction.
  const std::size_t capacity_;
  const std::size_t mask_;
  const std::unique_ptr<T[]> slots_;
  Doorbell* const consumerBell_;
  Doorbell* const producerBell_;
  const WaitPolicy wait_;

  // Consumer's line: its index, its cached copy of the producer's index, its counters.
  alignas(kCacheLine) std::atomic<std::uint64_t> head_{0};
  std::uint64_t tailCache_ = 0;
  [[no_unique_address]] std::conditional_t<kCounting, ConsumerCounters, NoCounters> consumer_;

  // Producer's line.
  alignas(kCacheLine) std::atomic<std::uint64_t> tail_{0};
  std::uint64_t headCache_ = 0;
  [[no_unique_address]] std::conditional_t<kCounting, ProducerCounters, NoCounters> producer_;
};

}  // namespace raycube::queues
