#pragma once

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
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

// Compile-time, so that a queue without accounting carries no counters and no branches. With accounting on,
// the queue keeps the cached-index trick: the producer reads the consumer's index only when its cached copy
// says the queue is full, and at occupancy samples (occupancySamplePeriod).
enum class Accounting { kOff, kOn };

// Messages between two occupancy samples: every push call up to capacity 8, then one sample per eighth of the
// capacity, at most every 64 messages. Each sample costs the producer one read of the consumer's cache line.
inline std::size_t occupancySamplePeriod(std::size_t capacity) {
  return std::clamp<std::size_t>(std::bit_ceil(capacity) / 8, 1, 64);
}

// The slots a queue of this capacity takes: the capacity rounded up to a power of two, so that the wrap of
// its indices lands on slot 0 whatever the capacity.
inline std::size_t spscSlotsFor(std::size_t capacity) {
  return std::bit_ceil(capacity);
}

// Uninitialised storage for messages, carved into the slots of queues: slots are written before they are
// read (T is trivially copyable, so the allocation holds its objects), and a page no message was ever
// written to is never touched. A machine's FIFOs share one: each allocation of its own would have the
// allocator write its bookkeeping beside every queue, touching every queue's first page (on huge pages,
// 2 MB each) while the machine is set up, though most of 64 processors' FIFOs never fill.
template <class T>
class SlotStorage {
 public:
  explicit SlotStorage(std::size_t count)
      : count_(count),
        slots_(static_cast<T*>(::operator new[](count * sizeof(T), std::align_val_t{alignof(T)}))) {}
  ~SlotStorage() { ::operator delete[](slots_, std::align_val_t{alignof(T)}); }
  SlotStorage(const SlotStorage&) = delete;
  SlotStorage& operator=(const SlotStorage&) = delete;

  // The next `count` slots not handed out yet.
  std::span<T> take(std::size_t count) {
    if (count > count_ - taken_)
      throw std::length_error("SlotStorage: " + std::to_string(count) + " slots asked, " +
                              std::to_string(count_ - taken_) + " left");
    taken_ += count;
    return {slots_ + taken_ - count, count};
  }

 private:
  std::size_t count_, taken_ = 0;
  T* slots_;
};

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
  explicit SpscQueue(std::size_t capacity = kPaperFifoCapacity)
      : SpscQueue(SpscOptions{.capacity = capacity}) {}

  explicit SpscQueue(const SpscOptions& options) : SpscQueue(options, nullptr) {}

  // In slots of `storage`, which must outlive the queue.
  SpscQueue(const SpscOptions& options, SlotStorage<T>& storage) : SpscQueue(options, &storage) {}

 private:
  SpscQueue(const SpscOptions& options, SlotStorage<T>* shared)
      : capacity_(checkedCapacity(options.capacity)),
        mask_(spscSlotsFor(options.capacity) - 1),
        firstIndex_(options.firstIndex),
        own_(shared ? nullptr : std::make_unique<SlotStorage<T>>(mask_ + 1)),
        slots_((shared ? *shared : *own_).take(mask_ + 1).data()),
        consumerBell_(options.consumerBell),
        producerBell_(options.producerBell),
        wait_(options.wait) {
    head_.store(options.firstIndex, std::memory_order_relaxed);
    tail_.store(options.firstIndex, std::memory_order_relaxed);
    tailCache_ = headCache_ = options.firstIndex;
  }

 public:
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
    if constexpr (kCounting) bump(producer_.refusedPushes);
    waitForRoomUntil([&] {
      done += pushSome(messages.subspan(done));
      return done == messages.size();
    });
  }

  // In place, for large messages (a block of contributions): the free slot the next message goes to, to be
  // written there and then published; null while the queue is full. Until publish(), the producer neither
  // pushes nor claims again; a claimed slot may stay unpublished as long as the producer likes.
  T* claim() {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    bool refreshed = false;
    const bool free = room(tail, 1, refreshed) > 0;
    if constexpr (kCounting) producer_.claimRefreshed = refreshed;
    if (free) return &slots_[tail & mask_];
    if constexpr (kCounting) bump(producer_.refusedPushes);
    return nullptr;
  }
  // The same, waiting (as pushN: spin, yield, then sleep on the producer bell) while the queue is full.
  T& claimWaiting() {
    T* slot = claim();  // counts the refusal if the queue is full
    if (slot == nullptr) waitForRoomUntil([&] { return (slot = claim()) != nullptr; });
    return *slot;
  }
  void publish() {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed) + 1;
    publishTo(tail);
    if constexpr (kCounting) recordPush(tail, 1, producer_.claimRefreshed);
  }

  // ---- Consumer side: one thread only.

  // In place: the oldest message, read where it lies until release() pops it; null when empty.
  const T* front() {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (waiting(head, 1) == 0) {
      if constexpr (kCounting) bump(consumer_.emptyPops);
      return nullptr;
    }
    return &slots_[head & mask_];
  }
  void release() { releaseTo(head_.load(std::memory_order_relaxed) + 1); }

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
      // The indices count every message since construction: no per-message counters.
      s.pushed = tail_.load(std::memory_order_acquire) - firstIndex_;
      s.refusedPushes = read(producer_.refusedPushes);
      s.nanosBlockedFull = read(producer_.nanosBlockedFull);
      s.highWater = read(producer_.highWater);
      s.occupancySamples = read(producer_.occupancySamples);
      s.occupancySum = read(producer_.occupancySum);
      for (std::size_t b = 0; b < kOccupancyBuckets; ++b)
        s.occupancyHistogram[b] = read(producer_.histogram[b]);
      s.popped = head_.load(std::memory_order_acquire) - firstIndex_;
      s.emptyPops = read(consumer_.emptyPops);
      s.nanosBlockedEmpty = read(consumer_.nanosBlockedEmpty);
    }
    return s;
  }

 private:
  using Clock = std::chrono::steady_clock;
  using Counter = std::atomic<std::uint64_t>;  // one writer; atomic only so that stats() may read it live

  struct ProducerCounters {
    Counter refusedPushes{0}, nanosBlockedFull{0}, highWater{0}, occupancySamples{0}, occupancySum{0};
    std::array<Counter, kOccupancyBuckets> histogram{};
    std::uint64_t untilSample = 0;  // messages to push before the next occupancy sample
    bool claimRefreshed = false;    // claim() read the consumer's index (recorded at publish())
  };
  struct ConsumerCounters {
    Counter emptyPops{0}, nanosBlockedEmpty{0};
  };
  struct NoCounters {};

  std::size_t pushSome(std::span<const T> messages) {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    bool refreshed = false;
    const std::size_t n = std::min<std::size_t>(messages.size(), room(tail, messages.size(), refreshed));
    if (n > 0) {
      for (std::size_t i = 0; i < n; ++i) slots_[(tail + i) & mask_] = messages[i];
      publishTo(tail + n);
    }
    if constexpr (kCounting) recordPush(tail + n, n, refreshed);
    return n;
  }

  std::size_t popSome(std::span<T> out) {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    const std::size_t n = std::min<std::size_t>(out.size(), waiting(head, out.size()));
    if (n == 0) return 0;
    for (std::size_t i = 0; i < n; ++i) out[i] = slots_[(head + i) & mask_];
    releaseTo(head + n);
    return n;
  }

  // Producer, refused: waits for room (spin, yield, then sleep on the producer bell) and calls done() each
  // time there is some, until it returns true; the time counts as blocked on a full queue.
  template <class Done>
  void waitForRoomUntil(Done&& done) {
    const Clock::time_point start = startClock();
    do {
      waitUntil(
          producerBell_, [this] { return hasSpace(); }, wait_);
    } while (!done());
    if constexpr (kCounting) bump(producer_.nanosBlockedFull, elapsedNanos(start));
  }
  // Producer: the free slots from `tail`, reading the consumer's index once at most: where the cached copy
  // shows fewer than `wanted`, or for an occupancy sample (`refreshed` says whether it read it).
  std::size_t room(std::uint64_t tail, std::size_t wanted, bool& refreshed) {
    refreshed = capacity_ - (tail - headCache_) < wanted || sampleDue(wanted);
    if (refreshed) headCache_ = head_.load(std::memory_order_acquire);
    return capacity_ - (tail - headCache_);
  }
  // Producer: every slot before `tail` is written; the consumer may take them.
  void publishTo(std::uint64_t tail) {
    tail_.store(tail, std::memory_order_release);
    if (consumerBell_ != nullptr) consumerBell_->ring();
  }
  // Consumer: the messages from `head`, reading the producer's index where the cached copy shows fewer than
  // `wanted`.
  std::size_t waiting(std::uint64_t head, std::size_t wanted) {
    if (tailCache_ - head < wanted) tailCache_ = tail_.load(std::memory_order_acquire);
    return tailCache_ - head;
  }
  // Consumer: every slot before `head` is read; the producer may reuse them.
  void releaseTo(std::uint64_t head) {
    head_.store(head, std::memory_order_release);
    if (producerBell_ != nullptr) producerBell_->ring();
  }

  bool sampleDue(std::size_t messages) const {
    if constexpr (kCounting) return messages >= producer_.untilSample;
    return false;
  }

  // Occupancy after a push, read off the cached index where pushSome refreshed it: where the queue looked
  // full (so a refused push sees it full) and at samples. A busy queue costs one more read of the consumer's
  // index per sample period than without accounting.
  void recordPush(std::uint64_t tail, std::size_t n, bool refreshed) {
    const bool sample = n > 0 && n >= producer_.untilSample;  // then sampleDue was true: refreshed
    producer_.untilSample = sample ? occupancySamplePeriod(capacity_) : producer_.untilSample - n;
    if (!refreshed) return;
    const std::uint64_t occupancy = tail - headCache_;
    if (occupancy > read(producer_.highWater))
      producer_.highWater.store(occupancy, std::memory_order_relaxed);
    if (!sample) return;
    bump(producer_.occupancySamples);
    bump(producer_.occupancySum, occupancy);
    bump(producer_.histogram[occupancyBucket(occupancy, capacity_)]);
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
  const std::uint64_t firstIndex_;
  // Its own slots, or none where it takes them from a shared SlotStorage.
  const std::unique_ptr<SlotStorage<T>> own_;
  T* const slots_;
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
