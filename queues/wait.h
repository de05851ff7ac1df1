#pragma once

#include <chrono>
#include <thread>

#include "queues/doorbell.h"

namespace raycube::queues {

// 64 logical processors share 2 cores: spin only as long as a handoff from another core takes, yield so
// the thread that would unblock us can run, then sleep.
struct WaitPolicy {
  int spins = 128;
  int yields = 2;
};

inline void cpuRelax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Returns once ready() holds: spin, then yield, then sleep on bell. Without a bell, keeps yielding.
template <class Ready>
void waitUntil(Doorbell* bell, Ready&& ready, const WaitPolicy& policy = {}) {
  for (int i = 0; i < policy.spins; ++i) {
    if (ready()) return;
    cpuRelax();
  }
  for (int i = 0; i < policy.yields; ++i) {
    if (ready()) return;
    std::this_thread::yield();
  }
  if (bell != nullptr) {
    bell->sleepUntil(ready);
  } else {
    while (!ready()) std::this_thread::yield();
  }
}

template <class Ready>
void waitUntil(Doorbell& bell, Ready&& ready, const WaitPolicy& policy = {}) {
  waitUntil(&bell, ready, policy);
}

// As waitUntil on a bell, giving up after about `timeout`: whether ready() holds.
template <class Ready>
bool waitUntilFor(Doorbell& bell, Ready&& ready, std::chrono::nanoseconds timeout,
                  const WaitPolicy& policy = {}) {
  for (int i = 0; i < policy.spins; ++i) {
    if (ready()) return true;
    cpuRelax();
  }
  for (int i = 0; i < policy.yields; ++i) {
    if (ready()) return true;
    std::this_thread::yield();
  }
  return bell.sleepUntilFor(ready, timeout);
}

}  // namespace raycube::queues
