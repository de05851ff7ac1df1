#pragma once
// Every engine's watchdog (issue 41): a machine that has not terminated and in which, for a whole period, no
// processor finished a ray or moved a message, has stalled: a walk that does not end (a processor inside one
// step all that time), or a ray or the termination token lost (every processor waiting). The engine turns it
// into an error naming the processor, never a spin or a sleep forever.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "host/util/clock.h"

namespace raycube::host {

// How often an engine looks: a fraction of the period, so a stall is named within 1.1 periods.
inline constexpr std::chrono::milliseconds stallLookEvery(std::chrono::milliseconds period) {
  return period / 10 > std::chrono::milliseconds(1) ? period / 10 : std::chrono::milliseconds(1);
}

class StallWatch {
 public:
  StallWatch(std::size_t processors, std::chrono::milliseconds period)
      : period_(period), seen_(processors, 0), since_(Clock::now()) {}

  // stepsWorked(p): processor p's steps that moved rays so far (LogicalProcessor::stepsWorked). Whether the
  // machine has gone a whole period without any of them moving.
  template <class StepsWorkedOf>
  bool stalled(StepsWorkedOf&& stepsWorked) {
    bool moved = false;
    for (std::size_t p = 0; p < seen_.size(); ++p)
      if (const std::uint64_t now = stepsWorked(p); now != seen_[p]) {
        seen_[p] = now;
        moved = true;
      }
    const auto now = Clock::now();
    if (moved) since_ = now;
    return now - since_ >= period_;
  }

  std::chrono::milliseconds period() const { return period_; }

  // The error's first words: how long nothing moved.
  std::string headline() const {
    return "the machine stalled: no processor finished a ray or moved a message for " +
           std::to_string(period_.count()) + " ms, and it has not terminated";
  }

 private:
  std::chrono::milliseconds period_;
  std::vector<std::uint64_t> seen_;
  Clock::time_point since_;
};

}  // namespace raycube::host
