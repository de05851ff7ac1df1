#pragma once
// Progress on stderr that tells the truth. A run goes through named phases (reading, estimating,
// partitioning, pruning, cells, tracing, writing); within a phase a work counter is compared with an
// estimate of the phase's total work (for tracing: every ray of every tree, estimated from the sub-sampled
// pixels of 3.7.1), and the time left is extrapolated from the rate of the last few seconds (a machine's
// parallelism falls at the end of a run, and the rate with it). A reporter thread prints,
// quiet during the first second so short runs print nothing; workers pay one relaxed atomic add per batch.
//
// stderr is one line, so a process has one progress line: the command line opens it around a whole
// command, and a renderer's Progress joins it as a phase (or opens its own when none is open, as in tests
// and benchmarks).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "host/util/clock.h"

namespace raycube::host {

struct ProgressSnapshot {
  std::string phase;
  double fraction = -1;          // of the phase's estimated work, in [0, 1]; < 0 when no estimate was given
  double phaseSeconds = 0;       // since the phase began
  double remainingSeconds = -1;  // of the phase, at the recent rate; < 0 when unknown
  double runSeconds = 0;         // since the progress line was opened
};
// "tracing  42%  1.2 s, about 1.7 s left" (or "pruning  0.3 s" without an estimate).
std::string progressLine(const ProgressSnapshot& snapshot);

class Progress {
 public:
  // Opens the process's progress line, printing to `out` after `quietFor` while enabled.
  explicit Progress(bool enabled, std::FILE* out = stderr,
                    std::chrono::milliseconds quietFor = std::chrono::seconds(1));
  // A renderer's handle: joins the open progress line as phase `what` with `total` units of work (0: no
  // estimate), or opens its own line when none is open.
  Progress(std::string what, std::uint64_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Starts a phase: the work counter restarts from 0, `expectedWork` units are expected (0: unknown).
  void phase(const std::string& name, double expectedWork = 0);
  // `done` more units finished (any thread).
  void advance(std::uint64_t done) { line_->done_.fetch_add(done, std::memory_order_relaxed); }
  // For a driver that sums counters kept elsewhere (the machine's processors): the units done so far and
  // a better estimate of the phase's total, at once, so no snapshot sees one without the other. A smaller
  // count than one given before is ignored.
  void setWork(std::uint64_t done, double expectedWork);
  // The phase's work is all done, whatever the estimate said: 100%, nothing left.
  void complete();
  // The fraction never goes backwards within a phase (a raised estimate holds it until the work catches
  // up), never reaches 1 before complete(), and restarts with each phase.
  ProgressSnapshot snapshot() const;
  // Called with a snapshot at every phase, setWork and complete (not at advance, the workers' hot path),
  // on the thread that made the change: what a test or a report watches.
  using Listener = std::function<void(const ProgressSnapshot&)>;
  void listen(Listener listener);

 private:
  void open(bool enabled, std::FILE* out, std::chrono::milliseconds quietFor);
  void report(std::chrono::milliseconds quietFor);
  void print(const ProgressSnapshot& snapshot);
  void notify();
  double remainingSeconds(double phaseSeconds, double fraction) const;  // under mutex_

  Progress* line_;  // this, or the open line it joined
  static std::atomic<Progress*> open_;

  std::FILE* out_ = stderr;
  std::chrono::milliseconds quietFor_{0};
  Clock::time_point start_ = Clock::now();
  mutable std::mutex mutex_;  // guards the phase's name, start and shown fraction, and the reporter's state
  std::string phase_;
  Clock::time_point phaseStart_ = start_;
  std::atomic<double> expected_{0};
  std::atomic<std::uint64_t> done_{0};
  std::atomic<bool> complete_{false};
  mutable double shown_ = 0;  // the highest fraction a snapshot of this phase gave (under mutex_)
  mutable std::deque<std::pair<double, double>> recent_;  // (phase seconds, fraction): the recent rate
  Listener listener_;                                     // set before the work starts
  std::condition_variable stop_;
  bool stopping_ = false;
  bool printed_ = false;
  std::size_t lastWidth_ = 0;
  std::thread reporter_;
};

}  // namespace raycube::host
