#include "host/progress.h"

#include <cstdio>

namespace raycube::host {

using namespace std::chrono_literals;

Progress::Progress(std::string what, std::uint64_t total, bool enabled)
    : what_(std::move(what)), total_(total) {
  if (enabled && total > 0) reporter_ = std::thread([this] { report(); });
}

Progress::~Progress() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  stop_.notify_all();
  if (reporter_.joinable()) reporter_.join();
  if (printed_) std::fprintf(stderr, "\r%s: 100%%   \n", what_.c_str());
}

void Progress::report() {
  std::unique_lock lock(mutex_);
  // Quiet for the first second: short renders print nothing.
  if (stop_.wait_for(lock, 1s, [this] { return stopping_; })) return;
  do {
    const double fraction = double(done_.load(std::memory_order_relaxed)) / double(total_);
    std::fprintf(stderr, "\r%s: %3.0f%%", what_.c_str(), 100 * fraction);
    std::fflush(stderr);
    printed_ = true;
  } while (!stop_.wait_for(lock, 500ms, [this] { return stopping_; }));
}

}  // namespace raycube::host
