#pragma once
// Progress on stderr for renders longer than a second: a reporter thread samples an atomic counter that
// workers bump as they finish samples, so reporting costs them one relaxed increment per row.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace raycube::host {

class Progress {
 public:
  Progress(std::string what, std::uint64_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::uint64_t done) { done_.fetch_add(done, std::memory_order_relaxed); }

 private:
  void report();

  std::string what_;
  std::uint64_t total_;
  std::atomic<std::uint64_t> done_{0};
  std::mutex mutex_;
  std::condition_variable stop_;
  bool stopping_ = false;
  bool printed_ = false;
  std::thread reporter_;
};

}  // namespace raycube::host
