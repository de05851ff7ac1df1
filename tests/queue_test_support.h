#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <future>
#include <thread>

namespace raycube::queues::testing {

inline bool sanitized() {
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
  return true;
#else
  const char* env = std::getenv("RAYCUBE_SANITIZED");
  return env != nullptr && env[0] == '1';
#endif
}

// Full counts in release; sanitizers run ~50x slower, so they get a smaller but still racy workload.
inline std::uint64_t scaled(std::uint64_t release, std::uint64_t sanitizedCount) {
  return sanitized() ? sanitizedCount : release;
}

// A lost wake-up shows up as a hang: fail the test and end the process rather than hang CI.
inline void runWithTimeout(std::chrono::seconds limit, const std::function<void()>& body) {
  std::packaged_task<void()> task(body);
  std::future<void> done = task.get_future();
  std::thread runner(std::move(task));
  if (done.wait_for(limit) == std::future_status::timeout) {
    ADD_FAILURE() << "timed out after " << limit.count() << " s: a waiter missed its wake-up";
    std::fprintf(stderr, "timed out after %lld s: a waiter missed its wake-up\n",
                 static_cast<long long>(limit.count()));
    std::fflush(stderr);
    std::_Exit(1);
  }
  runner.join();
  done.get();  // rethrows what the body threw
}

// SplitMix64: a payload that differs for every sequence number, so torn or stale slots are caught.
inline std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace raycube::queues::testing
