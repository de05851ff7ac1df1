#pragma once
// The host's one clock for wall time: phases, progress, the engines' own wall figures.
#include <chrono>

namespace raycube::host {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace raycube::host
