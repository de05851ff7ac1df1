#include "queues/doorbell.h"

#if defined(__linux__)
#include <linux/futex.h>
#include <linux/membarrier.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <climits>
#include <ctime>
#else
#include <algorithm>
#include <thread>
#endif

namespace raycube::queues {

bool asymmetricFencesAvailable() {
#if defined(__linux__) && defined(SYS_membarrier)
  static const bool available = syscall(SYS_membarrier, MEMBARRIER_CMD_REGISTER_PRIVATE_EXPEDITED, 0, 0) == 0;
  return available;
#else
  return false;
#endif
}

#if defined(__linux__) && defined(SYS_futex)
// std::atomic<std::uint32_t> holds its value as a plain 32-bit word, which is what a futex waits on.
static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));

void sleepWhile(const std::atomic<std::uint32_t>& word, std::uint32_t seen) noexcept {
  // Returns at once if word no longer holds seen; EINTR and spurious returns are the callers' re-check.
  syscall(SYS_futex, reinterpret_cast<const std::uint32_t*>(&word), FUTEX_WAIT_PRIVATE, seen, nullptr,
          nullptr, 0);
}

void sleepWhileFor(const std::atomic<std::uint32_t>& word, std::uint32_t seen,
                   std::chrono::nanoseconds timeout) noexcept {
  const long long ns = timeout.count();
  const timespec relative{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
  syscall(SYS_futex, reinterpret_cast<const std::uint32_t*>(&word), FUTEX_WAIT_PRIVATE, seen, &relative,
          nullptr, 0);
}

void wakeAll(std::atomic<std::uint32_t>& word) noexcept {
  syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr,
          0);
}
#else
void sleepWhile(const std::atomic<std::uint32_t>& word, std::uint32_t seen) noexcept {
  word.wait(seen, std::memory_order_acquire);
}

// std::atomic::wait cannot time out: a short nap, the caller re-checking.
void sleepWhileFor(const std::atomic<std::uint32_t>& word, std::uint32_t seen,
                   std::chrono::nanoseconds timeout) noexcept {
  if (word.load(std::memory_order_acquire) == seen)
    std::this_thread::sleep_for(std::min(timeout, std::chrono::nanoseconds(1000000)));
}

void wakeAll(std::atomic<std::uint32_t>& word) noexcept {
  word.notify_all();
}
#endif

namespace {
// Registering costs an RCU grace period once the process has a second thread, and
// nothing before: register while the program starts, single-threaded, not when the first doorbell is made.
[[maybe_unused]] const bool registeredAtStart = asymmetricFencesAvailable();
}  // namespace

// Forces a full barrier on every CPU running one of our threads; a thread that is not running has passed
// one in its context switch. So a ringer's store before its sleeper-count load is visible to us now.
void Doorbell::heavyFence() const {
#if defined(__linux__) && defined(SYS_membarrier)
  if (asymmetric_ && syscall(SYS_membarrier, MEMBARRIER_CMD_PRIVATE_EXPEDITED, 0, 0) == 0) return;
#endif
  seqCstFence();
}

}  // namespace raycube::queues
