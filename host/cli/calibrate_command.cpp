// raycube calibrate: this machine measured, written as a platform (DIR/platform.xml) and a cost table in
// seconds (DIR/costs) that --platform and --costs take (issue 47).
#include <fmt/format.h>
#include <unistd.h>

#include <iostream>
#include <string>

#include "host/cli/commands.h"
#include "host/studies/calibration.h"

namespace raycube::host {
namespace {

struct CalibrateCommand {
  std::string out;
  CalibrationOptions options;
  bool noMpi = false;
};

void print(const MeasuredConstant& m, const char* unit) {
  std::cout << fmt::format("  {:<15} {:>10.4g} {:<4} {}\n", m.key, m.value, unit, m.how);
}

int runCalibrate(CalibrateCommand& cmd) {
  cmd.options.mpi = !cmd.noMpi;
  cmd.options.program = std::filesystem::read_symlink("/proc/self/exe");
  const Calibration c = calibrateThisMachine(cmd.options);
  std::cout << fmt::format("this machine: {} cores\ncosts (seconds of one core):\n", c.cores);
  for (const MeasuredConstant& m : c.costs) print(m, "s");
  std::cout << "link between two processors (shared-memory FIFOs):\n";
  print(c.latency, "s");
  print(c.bandwidth, "B/s");
  if (c.startupSeconds.empty()) std::cout << c.mpiNote << '\n';
  for (const auto& [ranks, s] : c.startupSeconds)
    std::cout << fmt::format("  start-up, {} ranks {:>7.3f} s    mpirun of an 8x8 render, median\n", ranks,
                             s);
  std::cout << fmt::format(
      "check: tetra 4 128x128 on one processor took {:.4g} CPU s, predicted {:.4g} s ({:.2f})\n",
      c.checkTraceSeconds, c.checkPredictedSeconds, c.checkPredictedSeconds / c.checkTraceSeconds);
  const auto [xml, costs] = writeCalibration(c, cmd.out);
  std::cout << fmt::format("wrote {} and {} (raycube render ... --platform {} --costs {})\n", xml.string(),
                           costs.string(), xml.string(), costs.string());
  return 0;
}

void addCalibrateSubcommand(CLI::App& app, CalibrateCommand& cmd) {
  CLI::App* calibrate = app.add_subcommand(
      "calibrate", "Measure this machine: a platform and a cost table in seconds for --platform and --costs");
  calibrate->add_option("--out", cmd.out, "Folder for platform.xml and costs")->required();
  calibrate
      ->add_option("--repetitions", cmd.options.repetitions, "Of each microbenchmark (the median is kept)")
      ->check(CLI::Range(1, 50));
  calibrate->add_flag("--no-mpi", cmd.noMpi, "Do not measure an MPI run's start-up with mpirun");
}

}  // namespace

RunCommand addCalibrateCommand(CLI::App& app) {
  return commandOf<CalibrateCommand>(app, addCalibrateSubcommand, runCalibrate);
}

}  // namespace raycube::host
