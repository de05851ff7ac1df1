#pragma once
// raycube calibrate: this machine measured, as a platform the emulator can run (issue 47). Each counted
// operation of the cost table (host/machine/emulated_platform.h) is timed on the real core/, node/ and
// queues/ code in loops, several repetitions, their median taken; the results are seconds, not
// flop-equivalents. Measurements differ from run to run; the files' structure does not.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host/machine/emulated_platform.h"

namespace raycube::host {

// One measured constant: its cost-file key, its value, and how it was measured (printed, and written as a
// comment beside it).
struct MeasuredConstant {
  std::string key;
  double value = 0;
  std::string how;
};

struct CalibrationOptions {
  int repetitions = 5;  // of each microbenchmark: the median is kept
  bool mpi = true;      // measure an N-rank run's start-up with mpirun, where there is one
  std::vector<int> startupRanks{2, 3, 5};
  std::filesystem::path program;  // this raycube, which mpirun starts
};

struct Calibration {
  int cores = 1;
  std::vector<MeasuredConstant> costs;  // every CostTable field, in seconds
  // The link between two processors: over the shared-memory FIFOs (the MPI loopback is not measured here).
  MeasuredConstant latency, bandwidth;
  // An N-rank MPI run's start-up (mpirun, MPI_Init, loading the program): seconds at each rank count; empty
  // when there is no mpirun, with the reason in mpiNote.
  std::vector<std::pair<int, double>> startupSeconds;
  std::string mpiNote;
  // The check: a 1x1 render of the calibration scene, its traced seconds against the table's prediction.
  double checkTraceSeconds = 0, checkPredictedSeconds = 0;
};

Calibration calibrateThisMachine(const CalibrationOptions& options);
// The cost table, each value with its measurement as a comment, and `unit seconds`.
std::string costFileOf(const Calibration& calibration);
// A SimGrid platform of `nodes` hosts node-0 ... and the manager, each at 1 Gflop/s with the machine's
// cores (a cost in seconds is charged at a host's own speed), joined through a switch by links of the
// measured latency and bandwidth.
std::string platformXmlOf(const Calibration& calibration, int nodes = 64);
// DIR/platform.xml and DIR/costs; returns the two paths.
std::pair<std::filesystem::path, std::filesystem::path> writeCalibration(const Calibration& calibration,
                                                                         const std::filesystem::path& dir);

}  // namespace raycube::host
