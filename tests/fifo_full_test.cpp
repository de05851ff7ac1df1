// The paper's flow control (--fifo-full lock, Priol & Bouatouch 3.5.2) on the engines that run it: the
// image is the reference's whenever a run completes, simulated time is the same on every run, and a cycle
// of processors locked on each other's full FIFOs is reported as the run's result, within seconds, never a
// hang (host/machine/deadlock.h).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "core/spd/balls.h"
#include "host/prepare/machine_checks.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using testing_support::completesAsReferenceOrDeadlocks;
using testing_support::deadlockOf;
using testing_support::expectValidCycle;
using testing_support::locking;
using testing_support::LockingCase;
using testing_support::lockingCases;
using testing_support::renderMachineWatched;
using testing_support::settingsFor;
using testing_support::uniformGrid;

MachineSettings emulatedLocking(int rows, int columns, std::size_t capacity, node::LightRayMode lights) {
  MachineSettings m = locking(uniformGrid(rows, columns, capacity, lights));
  m.emulate = builtinPlatform("ipsc1");
  return m;
}

TEST(FifoFull, LockingRunsThatCompleteGiveTheReferenceImageAtAnyProcessorsAndCapacity) {
  const core::Scene scene = core::makeBalls(1);
  const RenderSettings settings = settingsFor(32);
  const RenderResult reference = renderReference(scene, settings);
  int completed = 0;
  for (const LockingCase& c : lockingCases())
    for (const std::string engine : {"threads", "threads with jitter", "ipsc1"}) {
      MachineSettings m = locking(uniformGrid(c.rows, c.columns, c.capacity, c.lights));
      if (engine == "ipsc1") m.emulate = builtinPlatform("ipsc1");
      if (engine == "threads with jitter") m.jitterSeed = 11;  // random delays around every transport call
      completed += completesAsReferenceOrDeadlocks(scene, reference, settings, m,
                                                   fmt::format("{} {}x{} capacity {} lights {}", engine,
                                                               c.rows, c.columns, c.capacity, int(c.lights)));
    }
  EXPECT_GE(completed, 9) << "most of these runs complete; a test that never compares proves nothing";
}

TEST(FifoFull, EmulatedLockingGivesTheSameSimulatedTimeOnEveryRun) {
  const core::Scene scene = core::makeBalls(2);
  // FIFOs of 8 rays, light rays as messages: 637 locks, no deadlock (FIFOs of 4 deadlock at 13.5 s).
  const MachineSettings m = emulatedLocking(4, 4, 8, node::LightRayMode::Messages);
  std::vector<MachineReport> reports(2);
  for (MachineReport& r : reports) renderMachineWatched(scene, settingsFor(48), m, r, "determinism");
  ASSERT_TRUE(reports[0].emulated && reports[1].emulated);
  EXPECT_EQ(reports[0].emulated->makespan, reports[1].emulated->makespan);
  std::uint64_t locks = 0;
  for (std::size_t p = 0; p < reports[0].processors.size(); ++p) {
    EXPECT_EQ(reports[0].processors[p].blockedSeconds, reports[1].processors[p].blockedSeconds) << p;
    EXPECT_EQ(reports[0].processors[p].node.locks, reports[1].processors[p].node.locks) << p;
    locks += reports[0].processors[p].node.locks;
  }
  EXPECT_GT(locks, 0u) << "the run never locked: pick a smaller capacity";
}

// FIFOs of one ray, light rays as messages, 16 processors: a cycle of locked processors forms at once in
// simulated time, always the same one at the same instant.
TEST(FifoFull, EmulatedDeadlockIsReportedWithItsCycleAndInstant) {
  const core::Scene scene = core::makeBalls(2);
  const MachineSettings m = emulatedLocking(4, 4, 1, node::LightRayMode::Messages);
  std::vector<Deadlock> found;
  for (int run = 0; run < 2; ++run) {
    MachineReport report;
    const std::optional<Deadlock> d = deadlockOf(scene, settingsFor(48), m, report, "emulated deadlock");
    ASSERT_TRUE(d) << "the run completed: no deadlock to detect";
    expectValidCycle(*d, report, 1);
    EXPECT_GT(d->simulatedSeconds, 0);
    ASSERT_TRUE(report.emulated);
    EXPECT_LE(d->simulatedSeconds, report.emulated->makespan);
    found.push_back(*d);
  }
  EXPECT_EQ(found[0].simulatedSeconds, found[1].simulatedSeconds);
  ASSERT_EQ(found[0].cycle.size(), found[1].cycle.size());
  for (std::size_t k = 0; k < found[0].cycle.size(); ++k)
    EXPECT_EQ(found[0].cycle[k].from, found[1].cycle[k].from);
}

// The same on threads: a cycle that stands with none of its processors stepping is proved a deadlock and
// stops the machine within seconds (the watchdog's limit is minutes).
TEST(FifoFull, ThreadsDeadlockIsDetectedAndStopsTheMachine) {
  const core::Scene scene = core::makeBalls(2);
  const MachineSettings m = locking(uniformGrid(4, 4, 1, node::LightRayMode::Messages));
  int deadlocks = 0;
  for (int run = 0; run < 3 && deadlocks == 0; ++run) {
    MachineReport report;
    const std::optional<Deadlock> d = deadlockOf(scene, settingsFor(64), m, report, "threads deadlock");
    if (!d) continue;  // thread timing let this one through
    ++deadlocks;
    expectValidCycle(*d, report, 1);
    EXPECT_LT(d->simulatedSeconds, 0) << "threads have no simulated clock";
    EXPECT_GT(d->wallSeconds, 0);
  }
  EXPECT_EQ(deadlocks, 1) << "three runs at capacity 1 all completed: no deadlock was constructed";
}

TEST(FifoFull, LockCycleFindsTheCycleAndNothingElse) {
  EXPECT_TRUE(lockCycle({-1, -1, -1}).empty());
  EXPECT_TRUE(lockCycle({1, 2, -1}).empty()) << "a chain ending at a processor that is not locked";
  EXPECT_EQ(lockCycle({-1, 3, -1, 1}), (std::vector<int>{1, 3}));
  EXPECT_EQ(lockCycle({1, 2, 4, 2, 3}), (std::vector<int>{2, 4, 3}));
  EXPECT_EQ(lockCycle({4, -1, -1, -1, 0}), (std::vector<int>{0, 4}));
}

}  // namespace
}  // namespace raycube::host
