#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>

#include "queues/cache_line.h"

namespace raycube::queues {

// Whether ring() pays for the store-load fence (kSymmetric: a locked instruction on every ring) or the
// sleeper does (kAsymmetric: one membarrier system call per sleep, so ringing costs a plain load).
enum class FenceMode { kAsymmetric, kSymmetric };

// True if the kernel offers expedited private membarrier; registers the process on first call.
bool asymmetricFencesAvailable();

// Sleeps while word holds seen (or until woken; callers re-check), and wakes every sleeper on word: the
// kernel's futex itself on Linux. std::atomic::wait spins and yields first (libstdc++ 12: four
// sched_yield calls before its futex), on top of the processors' own wait (WaitPolicy): many of a busy
// run's yields, each a system call that switched threads.
void sleepWhile(const std::atomic<std::uint32_t>& word, std::uint32_t seen) noexcept;
// The same, waking after `timeout` at the latest (a watchdog's look at a machine that may have stalled).
void sleepWhileFor(const std::atomic<std::uint32_t>& word, std::uint32_t seen,
                   std::chrono::nanoseconds timeout) noexcept;
void wakeAll(std::atomic<std::uint32_t>& word) noexcept;

// One doorbell per logical processor: every queue that feeds the processor rings it, and the processor
// sleeps on it when it has nothing to do. Ringing costs one load unless someone is asleep (see FenceMode).
class Doorbell {
 public:
  // kAsymmetric falls back to kSymmetric where membarrier is missing.
  explicit Doorbell(FenceMode mode = FenceMode::kAsymmetric)
      : asymmetric_(mode == FenceMode::kAsymmetric && asymmetricFencesAvailable()) {}

  Doorbell(const Doorbell&) = delete;
  Doorbell& operator=(const Doorbell&) = delete;

  // Call after publishing whatever the sleeper's predicate looks at.
  void ring() noexcept {
    lightFence();  // pairs with heavyFence in sleepUntil: either we see the sleeper or it sees our message
    if (sleepers_.load(std::memory_order_relaxed) != 0) {
      epoch_.fetch_add(1, std::memory_order_release);
      wakeAll(epoch_);
    }
  }

  // Blocks until ready() holds. ready() is re-checked after every wake-up, so extra rings are harmless,
  // and a ring between the check and the sleep changes the epoch, so it cannot be missed.
  template <class Ready>
  void sleepUntil(Ready&& ready) {
    sleepers_.fetch_add(1, std::memory_order_relaxed);
    heavyFence();
    for (;;) {
      const std::uint32_t seen = epoch_.load(std::memory_order_acquire);
      if (ready()) break;
      sleepWhile(epoch_, seen);
    }
    sleepers_.fetch_sub(1, std::memory_order_relaxed);
  }

  // As sleepUntil, but returns after about `timeout` even if ready() does not hold: whether it holds.
  template <class Ready>
  bool sleepUntilFor(Ready&& ready, std::chrono::nanoseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    sleepers_.fetch_add(1, std::memory_order_relaxed);
    heavyFence();
    bool holds = false;
    for (;;) {
      const std::uint32_t seen = epoch_.load(std::memory_order_acquire);
      if ((holds = ready())) break;
      const auto left = deadline - std::chrono::steady_clock::now();
      if (left <= std::chrono::nanoseconds(0)) break;
      sleepWhileFor(epoch_, seen, left);
    }
    sleepers_.fetch_sub(1, std::memory_order_relaxed);
    return holds;
  }

  FenceMode fenceMode() const { return asymmetric_ ? FenceMode::kAsymmetric : FenceMode::kSymmetric; }

 private:
  void lightFence() const noexcept {
    if (asymmetric_) {
      std::atomic_signal_fence(std::memory_order_seq_cst);  // the compiler must not swap store and load
    } else {
      seqCstFence();
    }
  }
  void heavyFence() const;  // membarrier, or a seq_cst fence

  static void seqCstFence() noexcept {
#if defined(__SANITIZE_THREAD__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored \
    "-Wtsan"  // TSAN does not model fences; our data still syncs via acquire/release
#endif
    std::atomic_thread_fence(std::memory_order_seq_cst);
#if defined(__SANITIZE_THREAD__)
#pragma GCC diagnostic pop
#endif
  }

  alignas(kCacheLine) std::atomic<std::uint32_t> epoch_{0};
  std::atomic<std::uint32_t> sleepers_{0};
  const bool asymmetric_;
};

}  // namespace raycube::queues
