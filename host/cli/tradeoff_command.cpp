// raycube tradeoff: what partitions and FIFO capacities cost, render by render.
#include <fmt/format.h>

#include <iostream>
#include <string>
#include <tuple>
#include <vector>

#include "core/image.h"
#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "core/spd/generators.h"
#include "host/chart/chart.h"
#include "host/cli/commands.h"
#include "host/cli/options.h"
#include "host/report/run_report.h"
#include "host/studies/tradeoff.h"
#include "host/util/progress.h"

namespace raycube::host {
namespace {

struct TradeoffCommand {
  std::string scenePath;
  int balls = 0;
  std::string spd;
  std::string size = "256x256";
  int runs = 3;
  int processors = 16;
  std::string csv = "out/tradeoff.csv";
  std::string plot = "out/tradeoff.png";
  std::string reportPath;
  std::string fromCsv;
};

// `raycube tradeoff`: the knobs' speed against their error, as a table, CSV and a plot.
int runTradeoff(const TradeoffCommand& cmd) {
  RenderCommand sceneCmd;
  sceneCmd.scenePath = cmd.scenePath;
  sceneCmd.balls = cmd.balls;
  sceneCmd.spd = cmd.spd;
  const core::Scene scene = loadScene(sceneCmd);
  RenderSettings base;
  std::tie(base.width, base.height) = parsePair(cmd.size, "--size", "WxH", core::kMaxNffResolution);
  base.progress = false;
  TradeoffOptions options;
  options.runs = cmd.runs;
  std::vector<TradeoffRow> rows;
  std::string windows;
  if (!cmd.fromCsv.empty()) {
    rows = readTradeoffCsv(cmd.fromCsv);  // redraw only: the measurements are the CSV's
  } else {
    std::cerr << "rendering the converged reference (depth " << options.referenceDepth << ", "
              << options.referenceRaysPerSample << " rays per pixel)...\n";
    rows = measureTradeoff(scene, base, options, [](const TradeoffRow& r) {
      std::cerr << "  " << r.knob << " " << r.setting << ": " << fmt::format("{:.3f} s", r.seconds) << "\n";
    });
  }
  const std::string table = tradeoffTable(rows);
  std::cout << table;
  if (cmd.fromCsv.empty()) {
    std::cerr << "measuring the load-estimate window on " << cmd.processors << " processors...\n";
    windows = subsampleTable(measureSubsampling(scene, base, cmd.processors, cmd.runs));
    std::cout << "\n" << windows;
  }
  const std::string caption = fmt::format(
      "{}, {}x{}, image-parallel, median of {} runs; reference depth {}, {} rays per pixel", scene.name,
      base.width, base.height, cmd.runs, options.referenceDepth, options.referenceRaysPerSample);
  const LineChart plot = tradeoffPlot(rows, caption);
  if (cmd.fromCsv.empty()) {
    writeTradeoffCsv(rows, ensureParent(cmd.csv));
    std::cout << "wrote " << cmd.csv << '\n';
  }
  writeChart(plot, ensureParent(cmd.plot));
  std::cout << "wrote " << cmd.plot << '\n';
  if (!cmd.reportPath.empty()) {
    RunReport run;
    run.title = fmt::format("raycube tradeoff: {}", scene.name);
    run.settings = {{"scene", cmd.scenePath.empty() ? scene.name + " (built in)" : cmd.scenePath},
                    {"size", cmd.size},
                    {"runs per setting", std::to_string(cmd.runs)},
                    {"processors (sub-sampling study)", std::to_string(cmd.processors)}};
    run.summary = table + "\n" + windows;
    addChartSection(run, plot);
    writeReport(run, ensureParent(cmd.reportPath));
    std::cout << "wrote " << cmd.reportPath << '\n';
  }
  return 0;
}

void addTradeoffSubcommand(CLI::App& app, TradeoffCommand& cmd) {
  CLI::App* t = app.add_subcommand("tradeoff", "Measure speed against accuracy for each knob");
  t->add_option("scene", cmd.scenePath, "NFF scene file (default: the built-in balls scene)")
      ->check(CLI::ExistingFile);
  t->add_option("--balls", cmd.balls, "Built-in SPD balls scene of this size (1-6): --spd balls:N")
      ->check(CLI::Range(1, core::kMaxBallsSize))
      ->excludes("scene");
  addSpdOption(t, cmd.spd);
  t->get_option("--spd")->excludes("scene")->excludes("--balls");
  t->add_option("--size", cmd.size, "Image size WxH");
  t->add_option("--runs", cmd.runs, "Renders per setting (median time)")->check(CLI::Range(1, 100));
  t->add_option("--procs", cmd.processors, "Processors for the sub-sampling window study (BSP)")
      ->check(CLI::Range(1, 4096));
  t->add_option("--csv", cmd.csv, "Table as CSV");
  t->add_option("--plot", cmd.plot, "Error against time as a chart (.png or .svg)");
  t->add_option("--report", cmd.reportPath, "Write a self-contained HTML report (tables and plot)");
  t->add_option("--from-csv", cmd.fromCsv,
                "Measure nothing: redraw the plot (and report) from a CSV an earlier run wrote; give the "
                "--size and --runs it used, for the caption")
      ->check(CLI::ExistingFile);
}

}  // namespace

RunCommand addTradeoffCommand(CLI::App& app) {
  return commandOf<TradeoffCommand>(app, addTradeoffSubcommand, runTradeoff);
}

}  // namespace raycube::host
