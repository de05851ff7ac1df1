// Termination of the message-passing machine (Priol & Bouatouch 3.6, made safe by Safra's counting token,
// EWD 998): a run with the smallest FIFOs on the largest grid still finishes (no deadlock, 2.2), and under
// random delays around every transport operation termination is never declared while a ray is still alive:
// every image is the reference image and every contribution reached the host. Primaries held back for the
// machine's backlog are let go again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/spd/balls.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

struct Totals {
  std::uint64_t spawned = 0, finished = 0, contributions = 0, messages = 0, refused = 0;
};

Totals totalsOf(const MachineReport& report) {
  Totals t;
  for (const ProcessorReport& p : report.processors) {
    for (int k = 0; k < core::kRayKinds; ++k) {
      t.spawned += p.node.spawned[k];
      t.finished += p.node.finished[k];
      t.messages += p.node.messagesByKind[k];
    }
    t.contributions += p.node.processed.contributions;
    t.refused += p.node.refusedPushes;
  }
  return t;
}

void expectComplete(const RenderResult& reference, const RenderResult& machine, const MachineReport& report,
                    const std::string& label) {
  EXPECT_TRUE(core::bitIdentical(machine.image, reference.image))
      << label << ": image differs from the reference";
  const Totals t = totalsOf(report);
  EXPECT_EQ(t.spawned, t.finished) << label << ": rays spawned vs finished";
  EXPECT_EQ(t.finished, reference.counters.totalRays()) << label << ": rays vs the reference";
  EXPECT_EQ(report.contributionsAccumulated, t.contributions)
      << label << ": contributions accumulated vs sent";
  EXPECT_EQ(report.contributionsAccumulated, reference.counters.contributions) << label;
}

// 2.2: with one-ray FIFOs on 64 processors most sends are refused at some point; a node that blocked on a
// full neighbour would deadlock the ring of full queues.
TEST(TerminationTest, CapacityOneOnEightByEightFinishes) {
  const core::Scene scene = core::makeBalls(2);
  const int side = sanitized() ? 24 : 64;
  const RenderSettings settings = settingsFor(side);
  const RenderResult reference = renderReference(scene, settings);
  MachineSettings machine;
  machine.rows = 8;
  machine.columns = 8;
  machine.queueCapacity = 1;
  machine.lightRays = node::LightRayMode::Messages;  // the most traffic: light rays travel too
  MachineReport report;
  const RenderResult result = renderMachineWatched(scene, settings, machine, report, "balls2 8x8 capacity 1");
  expectComplete(reference, result, report, "balls2 8x8 capacity 1");
  const Totals t = totalsOf(report);
  EXPECT_GT(t.messages, 1000u) << "the run must actually stress the FIFOs";
  EXPECT_GT(t.refused, 0u) << "some sends must find a full FIFO";
  std::printf(
      "8x8 capacity 1, %dx%d: %llu messages, %llu refused pushes, %u token rounds, %llu token passes\n", side,
      side, (unsigned long long)t.messages, (unsigned long long)t.refused, report.tokenRounds,
      (unsigned long long)report.tokenPasses);
}

// Machine-wide back-pressure (node::scheduling::kMachineBacklogLimit) at its tightest: primaries held back
// from the first ray waiting anywhere until none waits. Processors sleeping for the release must be woken by
// it, or the run hangs; the image, the rays and the contributions are still the reference's, under random
// delays.
TEST(TerminationTest, PrimariesHeldForTheMachinesBacklogAreLetGo) {
  const core::Scene scene = core::makeBalls(2);
  const int side = sanitized() ? 24 : 48;
  const RenderSettings settings = settingsFor(side);
  const RenderResult reference = renderReference(scene, settings);
  std::uint64_t held = 0;
  for (unsigned seed : {0u, 1u, 2u}) {
    MachineSettings machine;
    machine.rows = 8;
    machine.columns = 8;
    machine.queueCapacity = 1;
    machine.backlogLimit = 1;
    machine.jitterSeed = seed;
    machine.lightRays = node::LightRayMode::Messages;
    const std::string label = "backlog limit 1, jitter seed " + std::to_string(seed);
    MachineReport report;
    const RenderResult result = renderMachineWatched(scene, settings, machine, report, label);
    expectComplete(reference, result, report, label);
    for (const ProcessorReport& p : report.processors) held += p.node.primariesHeld;
  }
  EXPECT_GT(held, 0u) << "the machine's backlog must have held primaries back";
}

template <class T>
std::string minMedianMax(std::vector<T> values) {
  std::sort(values.begin(), values.end());
  return std::to_string(values.front()) + "/" + std::to_string(values[values.size() / 2]) + "/" +
         std::to_string(values.back());
}

// Random delays on every send, receive and token pass: the schedules under which a careless termination
// detector declares the end while a ray sits in a FIFO or in a node's overflow list.
TEST(TerminationTest, NeverDeclaredEarlyUnderRandomDelays) {
  const core::Scene scene = core::makeBalls(2);
  const int runs = sanitized() ? 24 : 800;
  const int sides[] = {16, 20, 24};
  const int grids[][2] = {{2, 2}, {3, 3}, {4, 4}, {1, 5}};
  std::map<int, RenderResult> references;
  for (int side : sides) references.emplace(side, renderReference(scene, settingsFor(side)));

  std::vector<std::uint64_t> tokenPasses, messages;
  std::vector<std::uint32_t> rounds;
  int failures = 0;
  for (int run = 0; run < runs && failures < 5; ++run) {
    const int side = sides[run % 3];
    MachineSettings machine;
    machine.rows = grids[(run / 3) % 4][0];
    machine.columns = grids[(run / 3) % 4][1];
    machine.queueCapacity = std::size_t(1 + run % 4);
    machine.jitterSeed = unsigned(run + 1);
    // Mostly the heaviest traffic (light rays as messages), every third run the default pyramids.
    machine.lightRays = run % 3 == 2 ? node::LightRayMode::Pyramid : node::LightRayMode::Messages;
    const std::string label = "jitter seed " + std::to_string(machine.jitterSeed) + ", balls2 " +
                              std::to_string(side) + "px, " + std::to_string(machine.rows) + "x" +
                              std::to_string(machine.columns) + ", capacity " +
                              std::to_string(fifoRaysFor(machine));
    MachineReport report;
    const RenderResult result = renderMachineWatched(scene, settingsFor(side), machine, report, label);
    const int before = testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count();
    expectComplete(references.at(side), result, report, label);
    if (testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count() != before)
      ++failures;
    tokenPasses.push_back(report.tokenPasses);
    rounds.push_back(report.tokenRounds);
    messages.push_back(totalsOf(report).messages);
    EXPECT_GE(report.tokenRounds, 1u) << label;
  }
  EXPECT_EQ(failures, 0) << "stopped after " << tokenPasses.size() << " runs";
  const std::string summary = "runs " + std::to_string(tokenPasses.size()) +
                              "; token passes min/median/max " + minMedianMax(tokenPasses) +
                              "; token rounds " + minMedianMax(rounds) + "; ray messages " +
                              minMedianMax(messages);
  std::printf("%s\n", summary.c_str());
  RecordProperty("token_passes", minMedianMax(tokenPasses));
  RecordProperty("token_rounds", minMedianMax(rounds));
  RecordProperty("ray_messages", minMedianMax(messages));
}

}  // namespace
}  // namespace raycube::host
