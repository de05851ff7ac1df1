// The machine over MPI (host/engines/mpi/mpi_machine.h) renders exactly what the reference renders, bit for
// bit, on 2, 3 or 5 ranks (ctest runs this program under mpiexec at each): every ray spawned finishes once,
// every contribution reaches rank 0, no eye ray leaves its processor, termination is proved by the token
// across ranks, and a processor never has more rays in flight towards a neighbour than the FIFO's capacity.
// Rank 0 runs the tests; the other ranks serve the renders it sends, one after another.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/spd/balls.h"
#include "host/engines/mpi/mpi_session.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

struct Case {
  int rows, columns;
  std::size_t capacity;
  core::Precision precision;
  node::LightRayMode lightRays;
  unsigned jitterSeed;  // > 0: random delays around every transport operation
};

std::string nameOf(const Case& c, int ranks) {
  return std::to_string(ranks) + " ranks, " + std::to_string(c.rows) + "x" + std::to_string(c.columns) +
         ", capacity " + std::to_string(c.capacity) + ", " + core::nameOf(c.precision) + ", light rays " +
         (c.lightRays == node::LightRayMode::Messages ? "messages" : "pyramid") +
         (c.jitterSeed > 0 ? ", jitter seed " + std::to_string(c.jitterSeed) : "");
}

// Every grid at both capacities on each rank count; precision, light mode and jitter alternate so that
// every value meets every rank count and every grid.
std::vector<Case> casesFor(int ranks) {
  std::vector<Case> cases;
  const std::pair<int, int> grids[] = {{1, 1}, {2, 2}, {3, 5}, {4, 4}};
  int k = ranks;
  for (const auto& [rows, columns] : grids)
    for (std::size_t capacity : {std::size_t(1), std::size_t(128)}) {
      ++k;
      cases.push_back(Case{rows, columns, capacity, k % 2 ? core::Precision::Float : core::Precision::Double,
                           (k / 2) % 2 ? node::LightRayMode::Messages : node::LightRayMode::Pyramid,
                           (k / 4) % 2 ? unsigned(k) : 0u});
    }
  return cases;
}

int worldSize() {
  return hostMpiLink()->size();
}

// 3.1's grid on the ranks; the reference in the same precision.
TEST(MpiMachineTest, MatchesReferenceOnEveryGridAndCapacity) {
  const core::Scene scene = core::makeBalls(2);
  std::map<core::Precision, RenderResult> references;
  for (const Case& c : casesFor(worldSize())) {
    RenderSettings settings = settingsFor(32);
    settings.precision = c.precision;
    if (!references.contains(c.precision)) references.emplace(c.precision, renderReference(scene, settings));
    MachineSettings machine = uniformGrid(c.rows, c.columns, c.capacity, c.lightRays);
    machine.mpi = true;
    machine.jitterSeed = c.jitterSeed;
    const std::string label = nameOf(c, worldSize());
    MachineReport report;
    const RenderResult result = renderMachineWatched(scene, settings, machine, report, label);
    expectMachineMatchesReference(references.at(c.precision), result, report, label);

    // Every rank reported; the processors were shared out, idle ranks (more ranks than processors) too.
    ASSERT_TRUE(report.mpi) << label;
    const MpiRun& run = *report.mpi;
    ASSERT_EQ(int(run.ranks.size()), worldSize()) << label;
    int processors = 0;
    std::uint64_t raysOverMpi = 0;
    for (const RankReport& r : run.ranks) {
      processors += r.processors;
      raysOverMpi += r.raysSent;
      EXPECT_LE(r.rayMessages, r.raysSent) << label << ": rank " << r.rank;
      EXPECT_GE(r.rayMessages * run.rayBatch, r.raysSent)
          << label << ": rank " << r.rank << ": batches too big";
    }
    EXPECT_EQ(processors, c.rows * c.columns) << label;
    EXPECT_EQ(run.ranks.front().processors, 0) << label << ": the host runs no processor";
    std::uint64_t raysSent = 0;
    for (const ProcessorReport& p : report.processors)
      for (std::uint64_t n : p.node.sent) raysSent += n;
    EXPECT_LE(raysOverMpi, raysSent) << label;
    if (c.rows * c.columns > 1 && worldSize() > 2) {
      EXPECT_GT(raysOverMpi, 0u) << label << ": no ray crossed ranks";
    }
    // 3.5.2's bounded FIFOs hold across ranks: no FIFO, local or towards another rank, ever held more.
    for (const ProcessorReport& p : report.processors)
      for (const queues::QueueStats& q : p.outgoing) EXPECT_LE(q.highWater, c.capacity) << label;
    // Termination (3.6): the token went round the whole ring, across ranks, before it was declared.
    EXPECT_GE(report.tokenRounds, 1u) << label;
    for (const ProcessorReport& p : report.processors)
      EXPECT_GE(p.node.tokenVisits, 1u) << label << ": the token never reached processor " << p.node.id;
  }
}

// A BSP partition (3.7.1) has irregular neighbours and routes through non-adjacent processors.
TEST(MpiMachineTest, BspPartitionMatchesReference) {
  const core::Scene scene = core::makeBalls(2);
  const RenderSettings settings = settingsFor(40);
  const RenderResult reference = renderReference(scene, settings);
  MachineSettings machine;
  machine.rows = 3;
  machine.columns = 3;
  machine.queueCapacity = 4;
  machine.mpi = true;
  renderAndCompare(scene, reference, settings, machine,
                   "bsp of 9 on " + std::to_string(worldSize()) + " ranks");
}

// The paper's flow control over MPI (3.5.2): a sender with no credit towards a neighbour on another rank
// locks as on a full FIFO of its own rank. A run that completes gives the reference's image; one that
// deadlocks ends as a proved cycle of full FIFOs, never a hang.
TEST(MpiMachineTest, LockingRunsThatCompleteGiveTheReferenceImage) {
  const core::Scene scene = core::makeBalls(1);
  const RenderSettings settings = settingsFor(32);
  const RenderResult reference = renderReference(scene, settings);
  int completed = 0;
  for (const LockingCase& c : lockingCases()) {
    MachineSettings m = locking(uniformGrid(c.rows, c.columns, c.capacity, c.lights));
    m.mpi = true;
    completed += completesAsReferenceOrDeadlocks(
        scene, reference, settings, m,
        std::to_string(worldSize()) + " ranks, lock, " + std::to_string(c.rows) + "x" +
            std::to_string(c.columns) + " capacity " + std::to_string(c.capacity));
  }
  EXPECT_GE(completed, 3) << "most of these runs complete; a test that never compares proves nothing";
}

// FIFOs of one ray, light rays as messages, 16 processors: a cycle of locked processors forms, is proved
// from what the ranks report, and stops every rank within seconds; the ranks then serve the next render.
TEST(MpiMachineTest, LockingDeadlockIsProvedAndStopsEveryRank) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings m = locking(uniformGrid(4, 4, 1, node::LightRayMode::Messages));
  m.mpi = true;
  int deadlocks = 0;
  for (int run = 0; run < 3 && deadlocks == 0; ++run) {
    MachineReport report;
    const std::optional<Deadlock> d = deadlockOf(scene, settingsFor(64), m, report, "mpi deadlock");
    if (!d) continue;  // timing let this one through
    ++deadlocks;
    expectValidCycle(*d, report, 1);
    EXPECT_GT(d->wallSeconds, 0);
    EXPECT_LT(d->wallSeconds, 30) << "proved long after it formed";
  }
  EXPECT_EQ(deadlocks, 1) << "three runs at capacity 1 all completed: no deadlock was constructed";
  MachineSettings after = uniformGrid(2, 2, 128);
  after.mpi = true;
  const RenderSettings settings = settingsFor(24);
  renderAndCompare(scene, renderReference(scene, settings), settings, after, "the render after a deadlock");
}

}  // namespace
}  // namespace raycube::host

int main(int argc, char** argv) {
  return raycube::host::runUnderMpi(argc, argv, [&] {
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
  });
}
