// raycube render: a scene to OpenEXR and PNG, on any mode and engine, with its statistics, charts and report.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/image.h"
#include "core/nff_reader.h"
#include "core/spd/generators.h"
#include "host/chart/chart.h"
#include "host/chart/load_chart.h"
#include "host/cli/commands.h"
#include "host/cli/options.h"
#include "host/engines/engine_module.h"
#include "host/prepare/machine_checks.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "host/report/emulated_report.h"
#include "host/report/machine_stats.h"
#include "host/report/mpi_report.h"
#include "host/report/run_report.h"
#include "host/report/stats_report.h"
#include "host/util/progress.h"

namespace raycube::host {
namespace {

// A render's exit codes beyond 0 (done), 1 (an error) and 2 (a usage error): 3, non-finite colours;
// 4, the machine deadlocked (--fifo-full lock).
constexpr int kNonFiniteExitCode = 3;
constexpr int kDeadlockExitCode = 4;

RenderResult render(const core::Scene& scene, const RenderCommand& cmd, const RenderSettings& settings,
                    std::optional<MachineReport>& report) {
  switch (kModes.at(cmd.mode)) {
    case RenderMode::Reference:
      return renderReference(scene, settings);
    case RenderMode::ImageParallel:
      return renderImageParallel(scene, settings);
    case RenderMode::Machine: {
      MachineSettings machine = machineSettingsOf(cmd);
      // Without --procs, the default grid shrinks to fit a small image rather than fail on an option the
      // user never gave.
      std::tie(machine.rows, machine.columns) =
          cmd.procs.empty()
              ? defaultProcessorGrid(core::View(scene.camera, settings.width, settings.height,
                                                settings.sampling, settings.shading.raysPerSample))
              : parsePair(cmd.procs, "--procs", "RxC", kMaxProcessorsPerSide);
      report.emplace();
      return renderMachine(scene, settings, machine, &*report);
    }
  }
  throw std::invalid_argument("unknown mode");
}

// Returns the paths written.
std::vector<std::string> writeOutputs(const core::Image& image, const core::Scene& scene,
                                      const std::string& output) {
  if (!output.empty()) {
    const std::filesystem::path path(output);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    core::writeImage(image, path);
    return {path.string()};
  }
  std::filesystem::create_directories("out");
  std::vector<std::string> written;
  for (const char* ext : {".exr", ".png"}) {
    const std::filesystem::path path = std::filesystem::path("out") / (scene.name + ext);
    core::writeImage(image, path);
    written.push_back(path.string());
  }
  return written;
}

BarChart figure15(const MachineReport& report, const std::string& caption) {
  const LoadBalance balance = loadBalanceOf(report);
  return loadChart(balance.estimated, balance.actualInMetric, caption);
}

std::vector<std::pair<std::string, std::string>> settingsOf(const RenderCommand& cmd,
                                                            const core::Scene& scene,
                                                            const RenderResult& result) {
  std::vector<std::pair<std::string, std::string>> s{
      {"scene", cmd.scenePath.empty() ? scene.name + " (built in)" : cmd.scenePath},
      {"size", fmt::format("{}x{}", result.image.width, result.image.height)},
      {"mode", cmd.mode},
      {"sampling", cmd.sampling},
      {"depth", std::to_string(cmd.depth)},
      {"rays per pixel", std::to_string(cmd.spp)},
      {"min-weight", fmt::format("{:g}", cmd.minWeight)},
      {"precision", cmd.precision}};
  if (cmd.mode != "machine") return s;
  s.insert(s.end(), {{"processors", cmd.procs},
                     {"balance", cmd.balance},
                     {"load metric", cmd.loadMetric},
                     {"sub-sampling window", cmd.machine.subsampleWindow == kAutoWindow
                                                 ? std::string("auto")
                                                 : std::to_string(cmd.machine.subsampleWindow)},
                     {"light rays", cmd.lightRays},
                     {"FIFO capacity", std::to_string(fifoRaysFor(cmd.machine))},
                     {"full FIFO", cmd.fifoFull.empty() ? "engine's own" : cmd.fifoFull},
                     {"cells", cellsName(cellsFor(cmd.machine))},
                     {"cell level", std::to_string(cmd.machine.cellLevel)}});
  return s;
}

// --report: the image, settings, summary and, from the machine, the overlay, figure 15 and the
// per-processor table taken from the same JSON --stats writes.
RunReport renderRunReport(const RenderCommand& cmd, const core::Scene& scene, const RenderResult& result,
                          const MachineReport* report, const nlohmann::json& stats,
                          const std::string& caption) {
  RunReport run;
  run.title = fmt::format("raycube render: {}", scene.name);
  run.settings = settingsOf(cmd, scene, result);
  run.summary = summaryText(scene, result) + (report ? machineTable(*report) : "") +
                (report && report->emulated ? emulatedTable(*report) : "") +
                (report && report->mpi ? mpiTable(*report) : "");
  run.imagePng = pngBytes(result.image);
  if (!report) return run;
  addChartSection(run, loadOverlay(result.image, *report, caption));
  addChartSection(run, figure15(*report, caption));
  if (report->emulated) addChartSection(run, timelineChart(*report, caption));
  run.sections.push_back(processorTableSection(stats.at("machine").at("processors")));
  return run;
}

// Everything --overlay, --load-chart, --stats and --report ask for; returns the paths written.
std::vector<std::string> writeExtras(const RenderCommand& cmd, const core::Scene& scene,
                                     const RenderSettings& settings, const RenderResult& result,
                                     const std::optional<MachineReport>& report) {
  std::vector<std::string> written;
  std::string caption = runCaption(scene, settings, result);
  if (report) caption += ", " + partitionName(*report);
  if (!cmd.overlayPath.empty()) {
    if (!report) throw std::invalid_argument("--overlay needs --mode machine");
    writeChart(loadOverlay(result.image, *report, caption), ensureParent(cmd.overlayPath));
    written.push_back(cmd.overlayPath);
  }
  if (!cmd.loadChartPath.empty()) {
    if (!report) throw std::invalid_argument("--load-chart needs --mode machine");
    writeChart(figure15(*report, caption), ensureParent(cmd.loadChartPath));
    written.push_back(cmd.loadChartPath);
  }
  if (!cmd.tracePath.empty() || !cmd.timelinePath.empty()) {
    if (!report || !report->emulated)
      throw std::invalid_argument("--trace and --timeline need --emulate or --platform");
    if (!cmd.tracePath.empty()) writeChromeTrace(*report, ensureParent(cmd.tracePath));
    if (!cmd.timelinePath.empty())
      writeChart(timelineChart(*report, caption), ensureParent(cmd.timelinePath));
    for (const std::string& path : {cmd.tracePath, cmd.timelinePath})
      if (!path.empty()) written.push_back(path);
  }
  if (cmd.statsPath.empty() && cmd.reportPath.empty()) return written;
  nlohmann::json json = statsJson(scene, result);
  if (report) json["machine"] = machineJson(*report);
  if (report && report->emulated) json["simulated"] = emulatedJson(*report);
  if (report && report->mpi) json["mpi"] = mpiJson(*report);
  if (!cmd.statsPath.empty()) writeJson(json, cmd.statsPath);
  if (!cmd.reportPath.empty()) {
    writeReport(renderRunReport(cmd, scene, result, report ? &*report : nullptr, json, caption),
                ensureParent(cmd.reportPath));
    written.push_back(cmd.reportPath);
  }
  return written;
}

// --fifo-full lock stopped on a deadlock: the run's result. --stats gets the counts up to it, --timeline
// the states up to it (no image).
int reportDeadlock(const RenderCommand& cmd, const MachineReport& report, const MachineDeadlocked& deadlock) {
  if (!cmd.timelinePath.empty() && report.emulated) {
    writeChart(timelineChart(report, deadlock.what()), ensureParent(cmd.timelinePath));
    std::cout << "wrote " << cmd.timelinePath << '\n';
  }
  if (!cmd.statsPath.empty()) {
    nlohmann::json json{{"machine", machineJson(report)}};
    if (report.emulated) json["simulated"] = emulatedJson(report);
    writeJson(json, cmd.statsPath);
    std::cout << "wrote " << cmd.statsPath << '\n';
  }
  std::cerr << "raycube: " << deadlock.what() << '\n';
  return kDeadlockExitCode;
}

int runRender(const RenderCommand& cmd) {
  // Everything that can be checked before the scene is read is: a typo fails at once, not after a render.
  const bool machineMode = kModes.at(cmd.mode) == RenderMode::Machine;
  if (!machineMode && !cmd.overlayPath.empty()) throw std::invalid_argument("--overlay needs --mode machine");
  if (!machineMode && !cmd.loadChartPath.empty())
    throw std::invalid_argument("--load-chart needs --mode machine");
  if (!cmd.procs.empty()) parsePair(cmd.procs, "--procs", "RxC", kMaxProcessorsPerSide);
  if (cmd.transport == "mpi") {
    if (!machineMode) throw std::invalid_argument("--transport mpi needs --mode machine");
    if (!cmd.emulate.empty() || !cmd.platformPath.empty())
      throw std::invalid_argument("--transport mpi runs on real ranks: it excludes --emulate and --platform");
    if (!hostsMpiRanks()) throw std::invalid_argument("--transport mpi needs mpirun -np N (N >= 2)");
  }
  requireWritable(cmd.output, "--output", {".exr", ".png"});
  requireWritable(cmd.statsPath, "--stats", {});
  requireWritable(cmd.overlayPath, "--overlay", {".png", ".svg"});
  requireWritable(cmd.loadChartPath, "--load-chart", {".png", ".svg"});
  requireWritable(cmd.timelinePath, "--timeline", {".png", ".svg"});
  requireWritable(cmd.reportPath, "--report", {".html"});
  std::optional<MachineReport> report;
  std::optional<RenderResult> result;
  std::optional<core::Scene> scene;
  std::vector<std::string> written;
  {
    // One progress line for the whole command; the renderers' phases join it. It ends before anything
    // goes to stdout, so the two never share a terminal line.
    Progress progress(!cmd.quiet);
    progress.phase("reading");
    scene.emplace(loadScene(cmd));
    const RenderSettings settings = renderSettingsOf(cmd, *scene);
    progress.phase("preprocessing");
    try {
      result.emplace(render(*scene, cmd, settings, report));
    } catch (const MachineDeadlocked& deadlock) {
      return reportDeadlock(cmd, *report, deadlock);
    }
    progress.phase("writing");
    written = writeOutputs(result->image, *scene, cmd.output);
    const std::vector<std::string> extras = writeExtras(cmd, *scene, settings, *result, report);
    written.insert(written.end(), extras.begin(), extras.end());
  }
  for (const std::string& path : written) std::cout << "wrote " << path << '\n';
  std::cout << summaryText(*scene, *result);
  if (report) std::cout << machineTable(*report);
  if (report && report->emulated) std::cout << emulatedTable(*report);
  if (report && report->mpi) std::cout << mpiTable(*report);
  return result->counters.nonFinite > 0 ? kNonFiniteExitCode : 0;
}

void addRenderSubcommand(CLI::App& app, RenderCommand& cmd) {
  addRenderOptions(app.add_subcommand("render", "Render a scene to OpenEXR and PNG"), cmd, true);
}

}  // namespace

RunCommand addRenderCommand(CLI::App& app) {
  return commandOf<RenderCommand>(app, addRenderSubcommand, runRender);
}

}  // namespace raycube::host
