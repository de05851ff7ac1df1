#include "host/machine/deadlock.h"

#include <fmt/format.h>

#include <algorithm>

namespace raycube::host {
namespace {

const char* faceName(node::Face face) {
  constexpr const char* kNames[] = {"left", "right", "up", "down"};
  return kNames[std::size_t(face)];
}

}  // namespace

std::vector<int> lockCycle(const std::vector<int>& lockedOn) {
  const int n = int(lockedOn.size());
  // Each processor waits for one other at most: walk from each until the walk ends or meets itself.
  std::vector<int> seenFrom(std::size_t(n), -1);
  for (int start = 0; start < n; ++start) {
    int p = start;
    while (p >= 0 && p < n && seenFrom[std::size_t(p)] < 0) {
      seenFrom[std::size_t(p)] = start;
      p = lockedOn[std::size_t(p)];
    }
    if (p < 0 || p >= n || seenFrom[std::size_t(p)] != start) continue;  // ended, or met an older walk
    std::vector<int> cycle{p};
    for (int q = lockedOn[std::size_t(p)]; q != p; q = lockedOn[std::size_t(q)]) cycle.push_back(q);
    std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
    return cycle;
  }
  return {};
}

std::vector<int> DeadlockProof::look(const std::vector<int>& lockedOn,
                                     const std::vector<std::uint64_t>& stepsWorked, Clock::time_point now) {
  std::vector<int> cycle = lockCycle(lockedOn);
  std::vector<std::uint64_t> worked;
  for (int p : cycle) worked.push_back(stepsWorked.at(std::size_t(p)));
  if (cycle.empty() || cycle != candidate_ || worked != candidateWorked_) {  // new, or it moved: start over
    candidate_ = std::move(cycle);
    candidateWorked_ = std::move(worked);
    since_ = now;
    return {};
  }
  return now - since_ >= quiet_ ? candidate_ : std::vector<int>{};
}

std::string describe(const Deadlock& deadlock) {
  std::string path, fifos;
  for (const LockedFifo& f : deadlock.cycle) {
    path += fmt::format("{} -> ", f.from);
    fifos += fmt::format("{}{} to {} through its {} face, full at {} ray{}", fifos.empty() ? "" : "; ",
                         f.from, f.to, faceName(f.face), f.rays, f.rays == 1 ? "" : "s");
  }
  if (!deadlock.cycle.empty()) path += std::to_string(deadlock.cycle.front().from);
  std::string when;
  if (deadlock.simulatedSeconds >= 0) when = fmt::format(" at {:.6f} simulated s", deadlock.simulatedSeconds);
  if (deadlock.wallSeconds >= 0)
    when += fmt::format(" (proved after {:.2f} s of the run)", deadlock.wallSeconds);
  return fmt::format(
      "deadlock{}: processors {} are each locked on a full FIFO of the next (--fifo-full lock, 3.5.2): {}. "
      "Use --fifo-full overflow, a larger --queue-capacity, or --light-rays pyramid",
      when, path, fifos);
}

}  // namespace raycube::host
