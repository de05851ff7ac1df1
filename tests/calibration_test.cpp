// raycube calibrate (host/studies/calibration.h): what it writes is a platform and a cost table in seconds
// that --platform and --costs read back, and the emulator charges those seconds as written.
#include "host/studies/calibration.h"

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

const std::vector<std::string> kCostKeys{"sphereTest",  "coneTest",     "polygonTest", "polygonVertex",
                                         "patchTest",   "cellStep",     "raySegment",  "rayFinished",
                                         "raySpawned",  "contribution", "sendSeconds", "receiveSeconds",
                                         "relaySeconds"};

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
  const double* fields[] = {&p.costs.sphereTest,    &p.costs.coneTest,    &p.costs.polygonTest,
                            &p.costs.polygonVertex, &p.costs.patchTest,   &p.costs.cellStep,
                            &p.costs.raySegment,    &p.costs.rayFinished, &p.costs.raySpawned,
                            &p.costs.contribution,  &p.costs.sendSeconds, &p.costs.receiveSeconds,
                            &p.costs.relaySeconds};
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
  EXPECT_GT(p.costs.sphereTest, 0);
}

}  // namespace
}  // namespace raycube::host
