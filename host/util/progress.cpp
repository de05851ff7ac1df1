#include "host/util/progress.h"

#include <fmt/format.h>

#include <algorithm>

namespace raycube::host {
namespace {

using namespace std::chrono_literals;

// An estimate can be short (a sub-sample misses some work): never claim a phase finished before it ends.
constexpr double kMaxFractionBeforeTheEnd = 0.99;
// Below this fraction the rate says too little to extrapolate the time left.
constexpr double kMinFractionToExtrapolate = 0.01;
// The time left follows the rate over the last few seconds, sampled now and then.
constexpr double kRateWindowSeconds = 4;
constexpr double kRateSampleEverySeconds = 0.25;
// A recent rate below this share of the phase's mean rate says the work has stalled, not when it ends.
constexpr double kStalledRateShare = 0.2;
constexpr auto kReportEvery = 250ms;

std::string duration(double seconds) {
  if (seconds < 60) return fmt::format("{:.1f} s", seconds);
  return fmt::format("{}:{:02} min", int(seconds) / 60, int(seconds) % 60);
}

}  // namespace

std::atomic<Progress*> Progress::open_{nullptr};

std::string progressLine(const ProgressSnapshot& s) {
  std::string text = s.phase;
  if (s.fraction >= 0) text += fmt::format(" {:3.0f}%", 100 * s.fraction);
  text += "  " + duration(s.phaseSeconds);
  if (s.remainingSeconds >= 0) text += ", about " + duration(s.remainingSeconds) + " left";
  return text;
}

Progress::Progress(bool enabled, std::FILE* out, std::chrono::milliseconds quietFor) : line_(this) {
  open(enabled, out, quietFor);
}

Progress::Progress(std::string what, std::uint64_t total, bool enabled) : line_(open_.load()) {
  if (line_ == nullptr) {
    line_ = this;
    open(enabled, stderr, 1s);
  }
  line_->phase(what, double(total));
}

void Progress::open(bool enabled, std::FILE* out, std::chrono::milliseconds quietFor) {
  out_ = out;
  Progress* none = nullptr;
  open_.compare_exchange_strong(none, this);  // a nested line (tests) stays private
  quietFor_ = quietFor;
  if (enabled) reporter_ = std::thread([this, quietFor] { report(quietFor); });
}

Progress::~Progress() {
  if (line_ != this) return;  // a joined handle: the line goes on
  Progress* self = this;
  open_.compare_exchange_strong(self, nullptr);
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  stop_.notify_all();
  if (!reporter_.joinable()) return;
  reporter_.join();
  // A run that outlasted the quiet time ends its line, whether or not the reporter got to print.
  const double seconds = snapshot().runSeconds;
  if (printed_ || seconds >= std::chrono::duration<double>(quietFor_).count()) {
    const std::string done = fmt::format("done in {}", duration(seconds));
    std::fprintf(out_, "\r%-*s\n", int(std::max(lastWidth_, done.size())), done.c_str());
    std::fflush(out_);
  }
}

void Progress::phase(const std::string& name, double expectedWork) {
  if (line_ != this) return line_->phase(name, expectedWork);
  {
    std::lock_guard lock(mutex_);
    phase_ = name;
    phaseStart_ = Clock::now();
    expected_.store(expectedWork, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    complete_.store(false, std::memory_order_relaxed);
    shown_ = 0;
    recent_.clear();
  }
  notify();
}

void Progress::setWork(std::uint64_t done, double expectedWork) {
  {
    std::lock_guard lock(line_->mutex_);
    line_->expected_.store(expectedWork, std::memory_order_relaxed);
    line_->done_.store(std::max(done, line_->done_.load(std::memory_order_relaxed)),
                       std::memory_order_relaxed);
  }
  line_->notify();
}

void Progress::complete() {
  line_->complete_.store(true, std::memory_order_relaxed);
  line_->notify();
}

void Progress::listen(Listener listener) {
  line_->listener_ = std::move(listener);
}

void Progress::notify() {
  if (listener_) listener_(snapshot());
}

ProgressSnapshot Progress::snapshot() const {
  if (line_ != this) return line_->snapshot();
  const Clock::time_point now = Clock::now();
  ProgressSnapshot s;
  // Under the lock, so no snapshot mixes a phase with the next one's counters (the reporter and a
  // listener can take one at the same time).
  std::lock_guard lock(mutex_);
  s.phase = phase_;
  s.phaseSeconds = std::chrono::duration<double>(now - phaseStart_).count();
  s.runSeconds = std::chrono::duration<double>(now - start_).count();
  const double expected = expected_.load(std::memory_order_relaxed);
  if (complete_.load(std::memory_order_relaxed)) {
    s.fraction = 1;
    s.remainingSeconds = 0;
  } else if (expected > 0) {
    const double fraction =
        std::min(kMaxFractionBeforeTheEnd, double(done_.load(std::memory_order_relaxed)) / expected);
    shown_ = std::max(shown_, fraction);
    s.fraction = shown_;
    s.remainingSeconds = remainingSeconds(s.phaseSeconds, s.fraction);
  }
  return s;
}

double Progress::remainingSeconds(double phaseSeconds, double fraction) const {
  if (recent_.empty() || phaseSeconds - recent_.back().first >= kRateSampleEverySeconds)
    recent_.emplace_back(phaseSeconds, fraction);
  while (recent_.size() > 2 && phaseSeconds - recent_[1].first >= kRateWindowSeconds) recent_.pop_front();
  if (fraction < kMinFractionToExtrapolate || phaseSeconds <= 0) return -1;
  auto [since, from] = recent_.front();
  if (phaseSeconds - since < kRateSampleEverySeconds)
    since = from = 0;  // too short a window: the whole phase
  const double recentRate = (fraction - from) / (phaseSeconds - since), meanRate = fraction / phaseSeconds;
  // Work nearly stopped lately (one processor left with an expensive corner): no honest estimate.
  if (recentRate < kStalledRateShare * meanRate) return -1;
  return (1 - fraction) / recentRate;
}

void Progress::print(const ProgressSnapshot& snapshot) {
  const std::string text = progressLine(snapshot);
  // Pad over what a longer previous line left behind.
  std::fprintf(out_, "\r%-*s", int(std::max(lastWidth_, text.size())), text.c_str());
  std::fflush(out_);
  lastWidth_ = text.size();
  printed_ = true;
}

void Progress::report(std::chrono::milliseconds quietFor) {
  std::unique_lock lock(mutex_);
  if (stop_.wait_for(lock, quietFor, [this] { return stopping_; })) return;
  do {
    lock.unlock();
    const ProgressSnapshot s = snapshot();
    lock.lock();
    print(s);
  } while (!stop_.wait_for(lock, kReportEvery, [this] { return stopping_; }));
}

}  // namespace raycube::host
