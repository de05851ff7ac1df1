#pragma once
// Shared by the machine's test programs: sanitizer-aware sizes and a render that cannot hang CI.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <string>
#include <thread>

#include "host/machine.h"
#include "test_support.h"

namespace raycube::host::testing_support {

using raycube::testing_support::sanitized;

// A run that has not finished by then is deadlocked or has lost its termination: fail loudly, not hang CI.
inline std::chrono::seconds watchdogLimit() {
  return std::chrono::seconds(sanitized() ? 600 : 120);
}

inline RenderSettings settingsFor(int side, core::Sampling sampling = core::Sampling::Centers) {
  RenderSettings s;
  s.width = side;
  s.height = side;
  s.sampling = sampling;
  s.progress = false;
  return s;
}

// renderMachine on a worker thread; std::abort() (after saying why) if it does not finish in time.
inline RenderResult renderMachineWatched(const core::Scene& scene, const RenderSettings& settings,
                                         const MachineSettings& machine, MachineReport& report,
                                         const std::string& label) {
  std::packaged_task<RenderResult()> task([&] { return renderMachine(scene, settings, machine, &report); });
  std::future<RenderResult> done = task.get_future();
  std::thread worker(std::move(task));
  if (done.wait_for(watchdogLimit()) != std::future_status::ready) {
    std::fprintf(stderr,
                 "WATCHDOG: %s did not finish within %lld s (deadlock or lost termination); aborting\n",
                 label.c_str(), (long long)watchdogLimit().count());
    std::fflush(stderr);
    std::abort();
  }
  worker.join();
  return done.get();
}

}  // namespace raycube::host::testing_support
