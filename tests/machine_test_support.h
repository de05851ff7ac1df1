#pragma once
// Shared by the test programs that render: settings builders, a machine run that cannot hang CI, what is
// wrong with an image, and everything a machine run must agree on with the reference renderer.
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "host/machine/deadlock.h"
#include "host/render/render_machine.h"
#include "test_support.h"

namespace raycube::host::testing_support {

using namespace raycube::testing_support;

// A side x side render without progress output; threads 0 lets the image-parallel renderer choose.
inline RenderSettings settingsFor(int side, core::Sampling sampling = core::Sampling::Centers,
                                  int threads = 0) {
  RenderSettings s;
  s.width = side;
  s.height = side;
  s.sampling = sampling;
  s.threads = threads;
  s.progress = false;
  return s;
}

// The R x C grid of 3.1 (the BSP has its own tests, load_distribution_test).
inline MachineSettings uniformGrid(int rows, int columns, std::size_t capacity,
                                   node::LightRayMode lightRays = MachineSettings{}.lightRays) {
  MachineSettings m;
  m.rows = rows;
  m.columns = columns;
  m.balance = Balance::Uniform;
  m.queueCapacity = capacity;
  m.lightRays = lightRays;
  return m;
}

// renderMachine on a worker thread, under the watchdog.
inline RenderResult renderMachineWatched(const core::Scene& scene, const RenderSettings& settings,
                                         const MachineSettings& machine, MachineReport& report,
                                         const std::string& label) {
  return runWatched(watchdogLimit(), label + " (deadlock or lost termination)",
                    [&] { return renderMachine(scene, settings, machine, &report); });
}

// Index of the first pixel with a NaN or infinite channel, or -1.
inline long firstNonFinitePixel(const core::Image& image) {
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(image.pixels[i][c])) return long(i);
  return -1;
}

inline std::size_t nonFinitePixels(const core::Image& image) {
  std::size_t count = 0;
  for (const core::Color& c : image.pixels)
    count += std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) ? 0 : 1;
  return count;
}

// Where two images differ: for the messages of the comparisons below.
inline std::string describeDifference(const core::Image& a, const core::Image& b) {
  if (a.width != b.width || a.height != b.height)
    return "sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
           std::to_string(b.width) + "x" + std::to_string(b.height);
  const core::ImageDifference d = core::compareImages(a, b);
  std::size_t differing = 0;
  long first = -1;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (a.pixels[i][c] != b.pixels[i][c]) {
        if (first < 0) first = long(i);
        ++differing;
        break;
      }
  std::string text = std::to_string(differing) + " pixels differ, maxAbs " + std::to_string(d.maxAbs) + ", " +
                     std::to_string(d.pixelsOver) + " over one sRGB level";
  if (first >= 0)
    text += ", first at (" + std::to_string(first % a.width) + ", " + std::to_string(first / a.width) + ")";
  return text;
}

// Everything a machine run must agree on with the reference: the image bit for bit, every ray spawned
// finished once and as many of each kind as the reference traced, every contribution delivered, no NaN, and
// no eye ray sent to a neighbour (3.1; even from the eye itself, hither 0, in float: SPD lattice).
inline void expectMachineMatchesReference(const RenderResult& reference, const RenderResult& machine,
                                          const MachineReport& report, const std::string& label) {
  EXPECT_TRUE(core::bitIdentical(machine.image, reference.image))
      << label
      << ": image differs from the reference: " << describeDifference(machine.image, reference.image);

  std::array<std::uint64_t, core::kRayKinds> spawned{}, finished{}, messages{};
  std::uint64_t contributions = 0, nonFinite = 0;
  for (const ProcessorReport& p : report.processors) {
    for (int k = 0; k < core::kRayKinds; ++k) {
      spawned[k] += p.node.spawned[k];
      finished[k] += p.node.finished[k];
      messages[k] += p.node.messagesByKind[k];
    }
    contributions += p.node.processed.contributions;
    nonFinite += p.node.processed.nonFinite;
  }
  for (int k = 0; k < core::kRayKinds; ++k) {
    const char* kind = core::rayKindName(core::RayKind(k));
    EXPECT_EQ(spawned[k], finished[k]) << label << ": " << kind << " rays spawned vs finished";
    EXPECT_EQ(finished[k], reference.counters.rays[k]) << label << ": " << kind << " rays vs the reference";
    EXPECT_EQ(machine.counters.rays[k], reference.counters.rays[k])
        << label << ": reported " << kind << " rays";
  }
  EXPECT_EQ(report.contributionsAccumulated, contributions) << label << ": contributions accumulated vs sent";
  EXPECT_EQ(contributions, reference.counters.contributions) << label << ": contributions vs the reference";
  EXPECT_EQ(nonFinite, 0u) << label << ": non-finite contributions";
  EXPECT_EQ(reference.counters.nonFinite, 0u) << label << ": non-finite contributions in the reference";
  // 3.1: an eye ray lies inside the pyramid of its own pixel area.
  EXPECT_EQ(messages[std::size_t(core::RayKind::Eye)], 0u) << label << ": eye rays sent to a neighbour";
  EXPECT_EQ(int(report.processors.size()), report.settings.rows * report.settings.columns) << label;
}

inline void renderAndCompare(const core::Scene& scene, const RenderResult& reference,
                             const RenderSettings& settings, const MachineSettings& machine,
                             const std::string& label) {
  MachineReport report;
  const RenderResult result = renderMachineWatched(scene, settings, machine, report, label);
  expectMachineMatchesReference(reference, result, report, label);
}

// --- The paper's flow control (--fifo-full lock, 3.5.2) and its deadlocks (host/machine/deadlock.h).

inline MachineSettings locking(MachineSettings m) {
  m.fifoFull = node::FifoFull::Lock;
  return m;
}

// A deadlock as reported: a cycle of neighbours, each FIFO towards the next full.
inline void expectValidCycle(const Deadlock& d, const MachineReport& report, std::size_t capacity) {
  ASSERT_GE(d.cycle.size(), 2u);
  for (std::size_t k = 0; k < d.cycle.size(); ++k) {
    const LockedFifo& f = d.cycle[k];
    EXPECT_EQ(f.to, d.cycle[(k + 1) % d.cycle.size()].from) << "not a cycle";
    EXPECT_EQ(f.rays, capacity) << f.from << " -> " << f.to << ": a FIFO of the cycle is not full";
    EXPECT_GE(report.processors.at(std::size_t(f.from)).node.locks, 1u) << f.from << " never locked";
  }
  EXPECT_NE(describe(d).find("deadlock"), std::string::npos);
}

// What a deadlocking run throws, with the report it filled (the --stats counts up to the deadlock).
inline std::optional<Deadlock> deadlockOf(const core::Scene& scene, const RenderSettings& settings,
                                          const MachineSettings& m, MachineReport& report,
                                          const std::string& label) {
  try {
    renderMachineWatched(scene, settings, m, report, label);
  } catch (const MachineDeadlocked&) {
    EXPECT_TRUE(report.deadlock.has_value()) << label;
    return report.deadlock;
  }
  return std::nullopt;
}

// Grids, capacities and light modes a locking machine is run at: some lock often, one has FIFOs of one ray.
struct LockingCase {
  int rows, columns;
  std::size_t capacity;
  node::LightRayMode lights;
};
inline std::vector<LockingCase> lockingCases() {
  return {{1, 1, 1, node::LightRayMode::Messages},
          {2, 2, 128, node::LightRayMode::Messages},
          {4, 4, 512, node::LightRayMode::Messages},
          {3, 5, 8, node::LightRayMode::Pyramid},
          {4, 4, 128, node::LightRayMode::Pyramid}};
}

// A locking run: true when it completed with the reference's image; a deadlock is allowed (the paper's
// open question), but only as a proved cycle of full FIFOs.
inline bool completesAsReferenceOrDeadlocks(const core::Scene& scene, const RenderResult& reference,
                                            const RenderSettings& settings, const MachineSettings& m,
                                            const std::string& label) {
  MachineReport report;
  try {
    const RenderResult result = renderMachineWatched(scene, settings, m, report, label);
    expectMachineMatchesReference(reference, result, report, label);
    return true;
  } catch (const MachineDeadlocked&) {
    EXPECT_TRUE(report.deadlock) << label;
    if (report.deadlock) expectValidCycle(*report.deadlock, report, fifoRaysFor(m));
    return false;
  }
}

}  // namespace raycube::host::testing_support
