// raycube calibrate (host/studies/calibration.h): what it writes is a platform and a cost table in seconds
// that --platform and --costs read back, and the emulator charges those seconds as written.
#include "host/studies/calibration.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/spd/balls.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using testing_support::renderMachineWatched;
using testing_support::settingsFor;

const std::vector<std::string> kCostKeys{
    "sphereTest",   "coneTest",    "polygonTest", "polygonVertex", "patchTest",        "cellStep",
    "raySegment",   "rayFinished", "raySpawned",  "contribution",  "sendSeconds",      "receiveSeconds",
    "relaySeconds", "segmentClip", "regionTest",  "mappingStep",   "accumulateSeconds"};

std::filesystem::path freshFolder(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("raycube-calibration-test-" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(dir);
  return dir;
}

// Values a cost file prints exactly (4 significant digits), each cost a different one.
Calibration handMade() {
  Calibration c;
  c.cores = 2;
  for (std::size_t i = 0; i < kCostKeys.size(); ++i)
    c.costs.push_back({kCostKeys[i], double(i + 1) * 1.5e-9, "by hand"});
  c.latency = {"latency", 2e-6, "by hand"};
  c.bandwidth = {"bandwidth", 1e9, "by hand"};
  c.mpiNote = "not measured";
  return c;
}

TEST(Calibration, WhatItWritesParsesBackToTheSameCostsInSeconds) {
  const Calibration c = handMade();
  const auto [xml, costs] = writeCalibration(c, freshFolder("parse"));
  const EmulatedPlatform p = userPlatform(xml, costs);
  EXPECT_EQ(p.computeUnit, ComputeUnit::Seconds);
  EXPECT_EQ(p.routing, Routing::Direct);
  EXPECT_FALSE(p.nodeSpeed);
  // Written again from what was read, the file is the same: the round trip loses nothing.
  Calibration again = c;
  const double* fields[] = {&p.costs.sphereTest,    &p.costs.coneTest,         &p.costs.polygonTest,
                            &p.costs.polygonVertex, &p.costs.patchTest,        &p.costs.cellStep,
                            &p.costs.raySegment,    &p.costs.rayFinished,      &p.costs.raySpawned,
                            &p.costs.contribution,  &p.costs.sendSeconds,      &p.costs.receiveSeconds,
                            &p.costs.relaySeconds,  &p.costs.segmentClip,      &p.costs.regionTest,
                            &p.costs.mappingStep,   &p.costs.accumulateSeconds};
  for (std::size_t i = 0; i < kCostKeys.size(); ++i) {
    EXPECT_EQ(*fields[i], c.costs[i].value) << kCostKeys[i];
    again.costs[i].value = *fields[i];
  }
  EXPECT_EQ(costFileOf(again), costFileOf(c));
}

// `unit seconds`: a cost is seconds of the platform's node, whatever its speed (calibrate's hosts run at
// 1 Gflop/s): one processor charged a microsecond per ray segment takes a microsecond per segment.
TEST(Calibration, CostsInSecondsAreChargedAsWritten) {
  Calibration c = handMade();
  for (MeasuredConstant& m : c.costs) m.value = m.key == "raySegment" ? 1e-6 : 0;
  const auto [xml, costs] = writeCalibration(c, freshFolder("seconds"));
  MachineSettings m;
  m.rows = m.columns = 1;
  m.emulate = userPlatform(xml, costs);
  MachineReport report;
  renderMachineWatched(core::makeBalls(1), settingsFor(16), m, report, "seconds");
  const double segments = double(report.processors[0].node.processed.totalRays());
  EXPECT_NEAR(report.processors[0].computeSeconds, segments * 1e-6, 1e-9 * segments * 1e-6);
}

// A measurement (one repetition of each, no MPI): the numbers are this machine's and differ between runs,
// the file's lines do not: every cost, in order, finite and not negative, then the unit and the routing.
TEST(Calibration, AMeasuredFileHasEveryCostInItsPlace) {
  CalibrationOptions options;
  options.repetitions = 1;
  options.mpi = false;
  const Calibration c = calibrateThisMachine(options);
  ASSERT_EQ(c.costs.size(), kCostKeys.size());
  for (std::size_t i = 0; i < kCostKeys.size(); ++i) {
    EXPECT_EQ(c.costs[i].key, kCostKeys[i]);
    EXPECT_TRUE(std::isfinite(c.costs[i].value) && c.costs[i].value >= 0) << kCostKeys[i];
    EXPECT_FALSE(c.costs[i].how.empty());
  }
  EXPECT_GT(c.latency.value, 0);
  EXPECT_GT(c.bandwidth.value, 0);
  EXPECT_TRUE(c.startupSeconds.empty());
  const auto [xml, costs] = writeCalibration(c, freshFolder("measured"));
  const EmulatedPlatform p = userPlatform(xml, costs);
  EXPECT_EQ(p.computeUnit, ComputeUnit::Seconds);
  // The host's prices are seconds too, a machine's, not the flop-equivalent hand counts read as seconds.
  for (double price : {p.costs.segmentClip, p.costs.regionTest, p.costs.mappingStep})
    EXPECT_TRUE(price > 0 && price < 1e-4) << price;
  EXPECT_GT(p.costs.sphereTest, 0);
}

// --ranks N: every processor and the host on node-0, sharing its cores. Work without messages between
// processors (eye rays only, light pyramids held) and costs of a microsecond per ray segment: k processors
// on one core take k times as long as on k cores of their own, the sum of their work; and a second run
// gives the same simulated time to the last digit.
TEST(Calibration, ProcessorsSharingACoreTakeTheSumOfTheirWork) {
  auto run = [](int cores, int columns) {
    Calibration c = handMade();
    c.cores = cores;
    for (MeasuredConstant& m : c.costs) m.value = m.key == "raySegment" ? 1e-6 : 0;
    const auto [xml, costs] = writeCalibration(c, freshFolder(fmt::format("share{}-{}", cores, columns)));
    MachineSettings m;
    m.rows = 1;
    m.columns = columns;
    m.balance = Balance::Uniform;
    m.emulate = userPlatform(xml, costs);
    m.emulate->ranks = 2;
    RenderSettings s = settingsFor(32);
    s.shading.maxDepth = 1;
    MachineReport report;
    renderMachineWatched(core::makeBalls(1), s, m, report, "ranks");
    double work = 0;
    for (const ProcessorReport& p : report.processors) work += 1e-6 * double(p.node.processed.totalRays());
    return std::pair{report.emulated->makespan, work};
  };
  const auto [oneCore, work] = run(1, 4);
  EXPECT_GT(work, 0);
  EXPECT_NEAR(oneCore, work, 1e-3 * work);  // four processors on one core: their work, one after another
  const auto [fourCores, sameWork] = run(4, 4);
  EXPECT_EQ(sameWork, work);
  EXPECT_LT(fourCores, 0.5 * oneCore);  // on four cores, at most the largest share (balls 1 is uneven)
  EXPECT_EQ(run(1, 4).first, oneCore);  // determinism
}

}  // namespace
}  // namespace raycube::host
