// raycube scaling: table 2, the same render on more and more processors in simulated time.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spd/generators.h"
#include "host/chart/chart.h"
#include "host/cli/commands.h"
#include "host/cli/options.h"
#include "host/report/run_report.h"
#include "host/studies/scaling.h"
#include "host/util/progress.h"

namespace raycube::host {
namespace {

struct ScalingCommand {
  RenderCommand render;
  std::vector<int> processors{1, 4, 16, 32};
  std::string csv;
  std::string plot;
  double fit = 0;
};

// Table 2: the same render on 1, 4, 16, 32 ... processors in simulated time.
int runScaling(ScalingCommand& cmd) {
  if (cmd.render.emulate.empty() && cmd.render.platformPath.empty())
    throw std::invalid_argument(
        "scaling needs --emulate or --platform: wall time on this host cannot show it");
  requireWritable(cmd.csv, "--csv", {});
  requireWritable(cmd.plot, "--plot", {".png", ".svg"});
  requireWritable(cmd.render.reportPath, "--report", {".html"});
  const core::Scene scene = loadScene(cmd.render);
  RenderSettings settings = renderSettingsOf(cmd.render, scene);
  settings.progress = false;
  MachineSettings machine = machineSettingsOf(cmd.render);
  const std::vector<ScalingPoint> points = scalingStudy(scene, settings, machine, cmd.processors);
  const std::string table = scalingTable(points, scene, settings);
  std::cout << table;
  if (cmd.fit > 0) {
    if (points.front().processors != 1) throw std::invalid_argument("--fit needs 1 among --procs");
    std::cout << fmt::format("fit: a node speed of {:.6g} flop-equivalents/s makes one processor take {} s\n",
                             points.front().nodeSpeed * points.front().makespan / cmd.fit, cmd.fit);
  }
  if (!cmd.csv.empty()) writeScalingCsv(points, ensureParent(cmd.csv));
  const LineChart plot = scalingPlot(points, scene, settings, machine.emulate->name);
  if (!cmd.plot.empty()) {
    writeChart(plot, ensureParent(cmd.plot));
    std::cout << "wrote " << cmd.plot << '\n';
  }
  if (!cmd.render.reportPath.empty()) {
    RunReport run;
    run.title = fmt::format("raycube scaling: {} on {}", scene.name, machine.emulate->name);
    run.settings = {
        {"scene", cmd.render.scenePath.empty() ? scene.name + " (built in)" : cmd.render.scenePath},
        {"size", fmt::format("{}x{}", settings.width, settings.height)},
        {"platform", machine.emulate->name},
        {"processors", fmt::format("{}", fmt::join(cmd.processors, ", "))}};
    run.summary = table;
    addChartSection(run, plot);
    writeReport(run, ensureParent(cmd.render.reportPath));
    std::cout << "wrote " << cmd.render.reportPath << '\n';
  }
  return 0;
}

void addScalingSubcommand(CLI::App& app, ScalingCommand& cmd) {
  CLI::App* scaling =
      app.add_subcommand("scaling", "Table 2: simulated time, speedup and efficiency against processors");
  addRenderOptions(scaling, cmd.render, false);
  scaling->add_option("--procs", cmd.processors, "Processor counts, e.g. 1,4,16,32")
      ->delimiter(',')
      ->check(CLI::Range(1, kMaxProcessorsPerSide * kMaxProcessorsPerSide));
  scaling->add_option("--csv", cmd.csv, "The table as CSV");
  scaling->add_option("--plot", cmd.plot, "Speed-up against processors as a chart (.png or .svg)");
  scaling
      ->add_option("--fit", cmd.fit, "Print the node speed that makes one processor take this many seconds")
      ->check(CLI::PositiveNumber);
}

}  // namespace

RunCommand addScalingCommand(CLI::App& app) {
  return commandOf<ScalingCommand>(app, addScalingSubcommand, runScaling);
}

}  // namespace raycube::host
