// raycube plot: a chart from a CSV table.
#include <iostream>
#include <string>

#include "core/nff_reader.h"
#include "host/chart/chart.h"
#include "host/chart/csv_chart.h"
#include "host/cli/commands.h"
#include "host/cli/options.h"

namespace raycube::host {
namespace {

struct PlotCommand {
  std::string csv;
  std::string output = "out/plot.png";
  CsvChartStyle style;
};

// `raycube plot T.csv`: a line chart of a table measured elsewhere (benchmarks/spd_benchmark.sh).
int runPlot(const PlotCommand& cmd) {
  writeChart(lineChartFromCsv(cmd.csv, cmd.style), ensureParent(cmd.output));
  std::cout << "wrote " << cmd.output << '\n';
  return 0;
}

void addPlotSubcommand(CLI::App& app, PlotCommand& cmd) {
  CLI::App* plot = app.add_subcommand(
      "plot",
      "Line chart of a CSV table: first column x (its heading names the axis), one series per column");
  plot->add_option("csv", cmd.csv, "The table")->required()->check(CLI::ExistingFile);
  plot->add_option("-o,--output", cmd.output, "The chart (.png or .svg)");
  plot->add_option("--title", cmd.style.title, "Chart title");
  plot->add_option("--caption", cmd.style.caption, "Line under the chart: where the data came from");
  plot->add_option("--y-label", cmd.style.yLabel, "y axis label, with its unit");
  plot->add_flag("--log-x", cmd.style.logX, "Logarithmic x axis");
  plot->add_flag("--log-y", cmd.style.logY, "Logarithmic y axis");
}

}  // namespace

RunCommand addPlotCommand(CLI::App& app) {
  return commandOf<PlotCommand>(app, addPlotSubcommand, runPlot);
}

}  // namespace raycube::host
