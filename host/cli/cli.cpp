#include "host/cli/cli.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string_view>
#include <system_error>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/spd/balls.h"
#include "core/image.h"
#include "core/nff_reader.h"
#include "core/nff_writer.h"
#include "core/spd/generators.h"
#include "host/chart/chart.h"
#include "host/chart/csv_chart.h"
#include "host/chart/load_chart.h"
#include "host/render/render_machine.h"
#include "host/prepare/machine_checks.h"
#include "host/report/machine_stats.h"
#include "host/engines/engine_module.h"
#include "host/report/mpi_report.h"
#include "host/util/progress.h"
#include "host/report/run_report.h"
#include "host/render/sequential_renderers.h"
#include "host/studies/scaling.h"
#include "host/report/emulated_report.h"
#include "host/report/stats_report.h"
#include "host/studies/tradeoff.h"

namespace raycube::host {
namespace {

// 16x16 is the paper's 256 processors squared; 64x64 leaves room without exhausting threads.
constexpr int kMaxProcessorsPerSide = 64;

const std::map<std::string, RenderMode> kModes{{"reference", RenderMode::Reference},
                                               {"image-parallel", RenderMode::ImageParallel},
                                               {"machine", RenderMode::Machine}};
const std::map<std::string, node::LightRayMode> kLightRays{{"messages", node::LightRayMode::Messages},
                                                           {"cone", node::LightRayMode::Cone},
                                                           {"pyramid", node::LightRayMode::Pyramid}};
const std::map<std::string, node::CellStructure> kCellStructures{{"auto", node::CellStructure::Auto},
                                                                  {"paper", node::CellStructure::Paper},
                                                                  {"bvh", node::CellStructure::Bvh}};
const std::map<std::string, Balance> kBalances{
    {"auto", Balance::Auto}, {"uniform", Balance::Uniform}, {"bsp", Balance::Bsp}};
const std::map<std::string, LoadMetric> kLoadMetrics{{"rays", LoadMetric::Rays}, {"cost", LoadMetric::Cost}};
const std::map<std::string, core::Precision> kPrecisions{{"float", core::Precision::Float},
                                                         {"double", core::Precision::Double}};
const std::map<std::string, core::Sampling> kSamplings{{"centers", core::Sampling::Centers},
                                                       {"corners", core::Sampling::Corners}};

template <class Value>
std::vector<std::string> keysOf(const std::map<std::string, Value>& map) {
  std::vector<std::string> keys;
  for (const auto& entry : map) keys.push_back(entry.first);
  return keys;
}

struct RenderCommand {
  std::string scenePath;
  int balls = 0;
  std::string spd;  // NAME[:SIZE], a built-in SPD generator
  std::string size;
  int depth = 5;
  int spp = 1;
  double minWeight = 0;
  std::string precision = "double";
  std::string mode = "machine";
  int threads = 0;
  std::string sampling = "centers";
  std::string output;
  std::string statsPath;
  bool quiet = false;
  bool strict = false;  // refuse a degenerate polygon or patch instead of skipping it
  std::string procs;  // empty: 4x4, or what fits a smaller image
  std::string overlayPath;
  std::string loadChartPath;
  std::string reportPath;
  std::string lightRays = "pyramid";
  std::string cells = "auto";
  std::string balance = "auto";
  std::string loadMetric = "cost";
  std::string emulate;
  std::string platformPath;
  std::string costsPath;
  std::string tracePath;
  std::string timelinePath;
  std::string transport = "threads";
  MachineSettings machine;
};

// --emulate NAME | --platform FILE.xml, with --costs FILE: the machine to simulate, if any.
std::optional<EmulatedPlatform> emulatedPlatform(const RenderCommand& cmd) {
  if (!cmd.platformPath.empty()) return userPlatform(cmd.platformPath, cmd.costsPath);
  if (cmd.emulate.empty()) {
    if (!cmd.costsPath.empty()) throw std::invalid_argument("--costs needs --emulate or --platform");
    return std::nullopt;
  }
  EmulatedPlatform platform = builtinPlatform(cmd.emulate);
  if (!cmd.costsPath.empty()) applyCostFile(cmd.costsPath, platform);
  return platform;
}

// The machine's options as the command gave them (the processor grid aside).
MachineSettings machineSettingsOf(const RenderCommand& cmd) {
  MachineSettings machine = cmd.machine;
  machine.lightRays = kLightRays.at(cmd.lightRays);
  machine.cells = kCellStructures.at(cmd.cells);
  machine.balance = kBalances.at(cmd.balance);
  machine.loadMetric = kLoadMetrics.at(cmd.loadMetric);
  machine.emulate = emulatedPlatform(cmd);
  machine.mpi = cmd.transport == "mpi";
  return machine;
}

// "AxB" with both in [1, limit]; what names the option in the error. Digits only: a number that does not
// fit is an error, never wrapped into range.
std::pair<int, int> parsePair(const std::string& text, const char* what, const char* form, int limit) {
  const auto fail = [&] {
    return CLI::ValidationError(
        what, fmt::format("expected {} with both between 1 and {}, got '{}'", form, limit, text));
  };
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos) throw fail();
  const auto side = [&](std::string_view digits) {
    long long value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || value < 1 ||
        value > limit)
      throw fail();
    return int(value);
  };
  const std::string_view all(text);
  return {side(all.substr(0, x)), side(all.substr(x + 1))};
}

// CLI::Range lets NaN through (every comparison with it is false).
const CLI::Validator kNotNaN(
    [](const std::string& text) {
      double value = 0;
      if (CLI::detail::lexical_cast(text, value) && std::isnan(value)) return std::string("NaN is not a number");
      return std::string();
    },
    "", "NOT_NAN");

// Output files are checked before a render that may take minutes: the extension, and that the file can be
// created (its folder is created as writing would). A file that did not exist is removed again.
// `extensions`: the formats the option writes ("" for any file).
void requireWritable(const std::string& path, const char* option, const std::vector<std::string>& extensions) {
  if (path.empty()) return;
  const std::filesystem::path p(path);
  if (!extensions.empty()) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
      throw CLI::ValidationError(option, fmt::format("'{}': unknown extension '{}' (use {})", path,
                                                     p.extension().string(), fmt::join(extensions, " or ")));
  }
  std::error_code error;
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), error);
  const bool existed = std::filesystem::exists(p, error);
  if (std::filesystem::is_directory(p, error))
    throw CLI::ValidationError(option, fmt::format("'{}' is a directory", path));
  {
    std::ofstream probe(p, std::ios::app);
    if (!probe)
      throw CLI::ValidationError(option, fmt::format("cannot write '{}': {}", path,
                                                     std::error_code(errno, std::generic_category()).message()));
  }
  if (!existed) std::filesystem::remove(p, error);
}

// --spd NAME[:SIZE]: a built-in SPD generator and its size (0 for the SPD's default size).
struct SpdChoice {
  std::string name;
  int size = 0;
};

// Throws std::invalid_argument naming the known generators, or the sizes a generator accepts.
SpdChoice parseSpdChoice(const std::string& text) {
  const std::size_t colon = text.find(':');
  SpdChoice choice{text.substr(0, colon), 0};
  const core::SpdGenerator& generator = core::spdGenerator(choice.name);
  if (colon == std::string::npos) return choice;
  const std::string_view digits = std::string_view(text).substr(colon + 1);
  long long size = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), size);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || size < 1 ||
      size > generator.maxSize) {
    throw std::invalid_argument(fmt::format("{} size must be a whole number from 1 to {} (default {}), got '{}'",
                                            generator.name, generator.maxSize, generator.defaultSize, digits));
  }
  choice.size = int(size);
  return choice;
}

// Checks NAME[:SIZE] while the command line is parsed, before any work.
const CLI::Validator kSpdChoice(
    [](const std::string& text) {
      try {
        parseSpdChoice(text);
      } catch (const std::invalid_argument& e) {
        return std::string(e.what());
      }
      return std::string();
    },
    "NAME[:SIZE]", "SPD_SCENE");

// The one place warnings are printed: what reading a scene file found worth saying (core/README.md).
core::Scene loadScene(const RenderCommand& cmd) {
  if (!cmd.scenePath.empty()) {
    core::Scene scene = core::readNff(cmd.scenePath, core::NffOptions{.strict = cmd.strict});
    for (const std::string& warning : scene.warnings) std::cerr << "warning: " << warning << '\n';
    return scene;
  }
  if (!cmd.spd.empty()) {
    const SpdChoice choice = parseSpdChoice(cmd.spd);
    return core::makeSpdScene(choice.name, choice.size);
  }
  return core::makeBalls(cmd.balls > 0 ? cmd.balls : 2);  // the default scene: the paper's balls, size 2
}

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
          cmd.procs.empty() ? defaultProcessorGrid(core::View(scene.camera, settings.width, settings.height,
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

// Charts and reports go where the user points, creating the folder as the image outputs do.
std::filesystem::path ensureParent(const std::filesystem::path& path) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  return path;
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
                     {"sub-sampling window", std::to_string(cmd.machine.subsampleWindow)},
                     {"light rays", cmd.lightRays},
                     {"FIFO capacity", std::to_string(fifoRaysFor(cmd.machine))},
                     {"cells", cmd.cells},
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

RenderSettings renderSettingsOf(const RenderCommand& cmd, const core::Scene& scene) {
  RenderSettings settings;
  settings.width = scene.camera.width;
  settings.height = scene.camera.height;
  if (!cmd.size.empty())
    std::tie(settings.width, settings.height) = parsePair(cmd.size, "--size", "WxH", core::kMaxNffResolution);
  settings.sampling = kSamplings.at(cmd.sampling);
  settings.shading.maxDepth = cmd.depth;
  settings.shading.raysPerSample = cmd.spp;
  settings.shading.minWeight = cmd.minWeight;
  settings.precision = kPrecisions.at(cmd.precision);
  settings.threads = cmd.threads;
  settings.progress = !cmd.quiet;
  return settings;
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
    if (!report || !report->emulated) throw std::invalid_argument("--trace and --timeline need --emulate or --platform");
    if (!cmd.tracePath.empty()) writeChromeTrace(*report, ensureParent(cmd.tracePath));
    if (!cmd.timelinePath.empty()) writeChart(timelineChart(*report, caption), ensureParent(cmd.timelinePath));
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
    result.emplace(render(*scene, cmd, settings, report));
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
  return result->counters.nonFinite > 0 ? 3 : 0;
}

std::string spdSceneList() {
  std::string list;
  for (const core::SpdGenerator& generator : core::spdGenerators()) {
    list += fmt::format("  {:<9} default {:>2}, sizes 1-{:<2}  {}\n", generator.name, generator.defaultSize,
                        generator.maxSize, generator.contents);
  }
  return list;
}

void addSpdOption(CLI::App* app, std::string& spd) {
  std::string names;
  for (const core::SpdGenerator& generator : core::spdGenerators()) {
    names += fmt::format("{}{} {}", names.empty() ? "" : ", ", generator.name, generator.defaultSize);
  }
  app->add_option("--spd", spd,
                  "Built-in SPD scene NAME[:SIZE], SIZE defaulting to the SPD's default size (" + names +
                      "); `raycube spd` lists them")
      ->check(kSpdChoice);
}

// The options of a render; a scaling study takes the same, but a list of processor counts for --procs.
void addRenderOptions(CLI::App* render, RenderCommand& cmd, bool procsAsGrid) {
  render->add_option("scene", cmd.scenePath, "NFF scene file (default: the built-in balls scene)")
      ->check(CLI::ExistingFile);
  render->add_option("--balls", cmd.balls, "Built-in SPD balls (sphereflake) scene of this size (1-6): --spd balls:N")
      ->check(CLI::Range(1, core::kMaxBallsSize));
  addSpdOption(render, cmd.spd);
  render->add_option("--size", cmd.size, "Image size WxH (overrides the file's resolution)");
  render->add_option("--depth", cmd.depth, "Maximum ray tree depth, the eye ray being depth 1")
      ->check(CLI::Range(1, 64));
  render->add_option("--mode", cmd.mode, "machine (message passing) | reference | image-parallel")
      ->transform(CLI::IsMember(keysOf(kModes), CLI::ignore_case));
  render
      ->add_option("--spp", cmd.spp,
                   "Eye rays per pixel, stratified and jittered with a fixed seed per pixel")
      ->check(CLI::Range(1, 4096));
  render
      ->add_option(
          "--min-weight", cmd.minWeight,
          "Adaptive depth: spawn no reflected/refracted ray whose Ks/Kt weight is below this (0 = off)")
      ->check(kNotNaN & CLI::Range(0.0, 1.0));
  render
      ->add_option("--precision", cmd.precision,
                   "float | double: ray state and intersection arithmetic (and so the ray message size)")
      ->transform(CLI::IsMember(keysOf(kPrecisions), CLI::ignore_case));
  render->add_option("--threads", cmd.threads, "Worker threads for image-parallel (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  render->add_option("--sampling", cmd.sampling, "centers (one ray per pixel) | corners (SPD rule 6)")
      ->transform(CLI::IsMember(keysOf(kSamplings), CLI::ignore_case));
  if (procsAsGrid)
    render->add_option("--procs", cmd.procs,
                       "Logical processors as RxC (rows x columns), default 4x4; with --balance bsp only R*C "
                       "counts (at most 1024), with auto R x C is the grid it weighs against the BSP");
  render
      ->add_option_function<std::size_t>(
          "--queue-capacity", [&cmd](const std::size_t& rays) { cmd.machine.queueCapacity = rays; },
          "Rays per face FIFO: 512 on threads; the iPSC's 128 in emulated time and over MPI")
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 20));
  render
      ->add_option(
          "--cells", cmd.cells,
          "How a region holds its objects: paper (3.3's super-cells cut by depth faces) | bvh (a BVH, "
          "cost about logarithmic in the objects) | auto (bvh on real cores, where it costs less even in "
          "sparse regions; paper when emulating, the costs being fitted to it)")
      ->transform(CLI::IsMember(keysOf(kCellStructures), CLI::ignore_case));
  render
      ->add_option("--cell-level", cmd.machine.cellLevel,
                   "Recursive halvings of each pixel area into super-cells (paper cells)")
      ->check(CLI::Range(0, 8));
  render
      ->add_option("--light-rays", cmd.lightRays,
                   "messages (light rays travel) | cone | pyramid (traced where they start, 3.7.2)")
      ->transform(CLI::IsMember(keysOf(kLightRays), CLI::ignore_case));
  render
      ->add_option(
          "--balance", cmd.balance,
          "uniform (R x C grid, 3.1) | bsp (equal estimated loads, 3.7.1) | auto (whichever the "
          "sub-sampled estimate says finishes first on the cores the processors share: the BSP where "
          "each has its own, as emulated or on MPI; on threads sharing few cores, often the grid, "
          "which splits fewer rays into messages)")
      ->transform(CLI::IsMember(keysOf(kBalances), CLI::ignore_case));
  render
      ->add_option("--load-metric", cmd.loadMetric, "rays (the paper's) | cost (rays weighted by their work)")
      ->transform(CLI::IsMember(keysOf(kLoadMetrics), CLI::ignore_case));
  render
      ->add_option("--subsample", cmd.machine.subsampleWindow,
                   "Load estimate: one sub-sampled pixel per WxW window")
      ->check(CLI::Range(1, 1024));
  render
      ->add_option("--emulate", cmd.emulate,
                   "Run the machine on SimGrid in simulated time: ipsc1 (the paper's iPSC/1) | cluster")
      ->check(CLI::IsMember({"ipsc1", "cluster"}));
  render
      ->add_option("--transport", cmd.transport,
                   "threads (shared-memory FIFOs) | mpi (under mpirun -np N: rank 0 the host, ranks 1..N-1 "
                   "the processors; README, The machine over MPI)")
      ->check(CLI::IsMember({"threads", "mpi"}));
  render
      ->add_option("--ray-batch", cmd.machine.rayBatch, "MPI: rays per message to one rank, at most")
      ->check(CLI::Range(std::size_t(1), std::size_t(4096)));
  render->add_option("--platform", cmd.platformPath,
                     "A SimGrid platform XML to emulate (hosts node-0 ... and manager; see README)");
  render->add_option("--costs", cmd.costsPath, "Cost table: 'name value' lines (README, Emulated machine time)");
  render->add_option("--trace", cmd.tracePath, "Simulated timeline as Chrome trace-event JSON (Perfetto)");
  render->add_option("--timeline", cmd.timelinePath, "Simulated timeline as a chart (.png or .svg)");
  render->add_option("-o,--output", cmd.output,
                     "Output image (.exr or .png); default: out/<scene>.exr and .png");
  render->add_option("--stats", cmd.statsPath, "Write statistics as JSON to this file");
  render->add_option("--overlay", cmd.overlayPath,
                     "Machine: the image with its regions numbered and coloured by load (.png or .svg)");
  render->add_option(
      "--load-chart", cmd.loadChartPath,
      "Machine: figure 15, estimated against actual load per processor, as a bar chart (.png or .svg)");
  render->add_option("--report", cmd.reportPath,
                     "Write a self-contained HTML run report (image, settings, summary, charts, table)");
  render->add_flag("-q,--quiet", cmd.quiet, "No progress indication");
  render->add_flag(
      "--strict", cmd.strict,
      "Refuse an NFF file with a degenerate polygon or patch instead of skipping it with a warning");
  render->get_option("--balls")->excludes("scene");
  render->get_option("--spd")->excludes("scene")->excludes("--balls");
}

void addRenderCommand(CLI::App& app, RenderCommand& cmd) {
  addRenderOptions(app.add_subcommand("render", "Render a scene to OpenEXR and PNG"), cmd, true);
}

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
    throw std::invalid_argument("scaling needs --emulate or --platform: wall time on this host cannot show it");
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
                             machine.emulate->nodeSpeed * points.front().makespan / cmd.fit, cmd.fit);
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
    run.settings = {{"scene", cmd.render.scenePath.empty() ? scene.name + " (built in)" : cmd.render.scenePath},
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

void addScalingCommand(CLI::App& app, ScalingCommand& cmd) {
  CLI::App* scaling = app.add_subcommand("scaling", "Table 2: simulated time, speedup and efficiency against processors");
  addRenderOptions(scaling, cmd.render, false);
  scaling->add_option("--procs", cmd.processors, "Processor counts, e.g. 1,4,16,32")
      ->delimiter(',')
      ->check(CLI::Range(1, kMaxProcessorsPerSide * kMaxProcessorsPerSide));
  scaling->add_option("--csv", cmd.csv, "The table as CSV");
  scaling->add_option("--plot", cmd.plot, "Speed-up against processors as a chart (.png or .svg)");
  scaling->add_option("--fit", cmd.fit, "Print the node speed that makes one processor take this many seconds")
      ->check(CLI::PositiveNumber);
}

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

void addTradeoffCommand(CLI::App& app, TradeoffCommand& cmd) {
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

struct SpdCommand {
  std::string scene;  // NAME[:SIZE]; empty: list the generators
  std::string output;
};

// `raycube spd NAME[:SIZE] [-o FILE]`: the generated scene as NFF, the same text the SPD program prints.
int runSpd(const SpdCommand& cmd) {
  if (cmd.scene.empty()) {
    std::cout << "Built-in SPD generators (raycube spd NAME[:SIZE], render --spd NAME[:SIZE]):\n" << spdSceneList();
    return 0;
  }
  const SpdChoice choice = parseSpdChoice(cmd.scene);
  const core::Scene scene = core::makeSpdScene(choice.name, choice.size);
  if (cmd.output.empty() || cmd.output == "-") {
    core::writeNff(std::cout, scene);
    return 0;
  }
  std::ofstream file(ensureParent(cmd.output), std::ios::binary);
  core::writeNff(file, scene);
  file.close();
  if (!file) throw std::runtime_error(fmt::format("cannot write '{}'", cmd.output));
  std::cerr << fmt::format("wrote {} ({}: {} objects)\n", cmd.output, scene.name, scene.objects.size());
  return 0;
}

void addSpdCommand(CLI::App& app, SpdCommand& cmd) {
  CLI::App* spd = app.add_subcommand(
      "spd", "Write a built-in SPD scene as NFF (the SPD program's own output); without a scene, list them");
  spd->add_option("scene", cmd.scene, "NAME[:SIZE], SIZE defaulting to the SPD's default size")->check(kSpdChoice);
  spd->add_option("-o,--output", cmd.output, "NFF file to write (default: standard output)");
}

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

void addPlotCommand(CLI::App& app, PlotCommand& cmd) {
  CLI::App* plot = app.add_subcommand(
      "plot", "Line chart of a CSV table: first column x (its heading names the axis), one series per column");
  plot->add_option("csv", cmd.csv, "The table")->required()->check(CLI::ExistingFile);
  plot->add_option("-o,--output", cmd.output, "The chart (.png or .svg)");
  plot->add_option("--title", cmd.style.title, "Chart title");
  plot->add_option("--caption", cmd.style.caption, "Line under the chart: where the data came from");
  plot->add_option("--y-label", cmd.style.yLabel, "y axis label, with its unit");
  plot->add_flag("--log-x", cmd.style.logX, "Logarithmic x axis");
  plot->add_flag("--log-y", cmd.style.logY, "Logarithmic y axis");
}

struct CompareCommand {
  std::string first, second;
  std::string diffPath;
  double gain = 1;
};

// `raycube compare A B`: how far apart two renders are; exit 0 only when bit-identical.
int runCompare(const CompareCommand& cmd) {
  const core::Image a = core::readImage(cmd.first), b = core::readImage(cmd.second);
  const core::ImageDifference d = core::compareImages(a, b);
  const bool identical = core::bitIdentical(a, b);
  std::cout << fmt::format("rmse {:.3g}, psnr {:.2f} dB, max {:.3g}, pixels over 1/255: {}, {}\n", d.rmse,
                           d.psnr, d.maxAbs, d.pixelsOver, identical ? "bit-identical" : "different");
  if (!cmd.diffPath.empty()) core::writeImage(core::differenceImage(a, b, cmd.gain), cmd.diffPath);
  return identical ? 0 : 1;
}

void addCompareCommand(CLI::App& app, CompareCommand& cmd) {
  CLI::App* compare =
      app.add_subcommand("compare", "Compare two images (EXR or PNG); exit 0 if bit-identical");
  compare->add_option("first", cmd.first, "First image")->required()->check(CLI::ExistingFile);
  compare->add_option("second", cmd.second, "Second image")->required()->check(CLI::ExistingFile);
  compare->add_option("--diff", cmd.diffPath, "Write |first - second| (times --gain) to this EXR or PNG");
  compare->add_option("--gain", cmd.gain, "Scale of the difference image")->check(kNotNaN & CLI::Range(0.0, 1e12));
}

}  // namespace

int runCommandLine(int argc, char** argv) {
  CLI::App app{"raycube: Priol & Bouatouch's hypercube ray tracer (INRIA RR-0843, 1988), emulated"};
  app.require_subcommand(1);
  RenderCommand renderCmd;
  addRenderCommand(app, renderCmd);
  CompareCommand compareCmd;
  addCompareCommand(app, compareCmd);
  TradeoffCommand tradeoffCmd;
  addTradeoffCommand(app, tradeoffCmd);
  ScalingCommand scalingCmd;
  addScalingCommand(app, scalingCmd);
  PlotCommand plotCmd;
  addPlotCommand(app, plotCmd);
  SpdCommand spdCmd;
  addSpdCommand(app, spdCmd);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "raycube: " << e.what() << " (see raycube --help)\n";
    return 2;
  }
  try {
    if (app.got_subcommand("render")) return runRender(renderCmd);
    if (app.got_subcommand("compare")) return runCompare(compareCmd);
    if (app.got_subcommand("tradeoff")) return runTradeoff(tradeoffCmd);
    if (app.got_subcommand("scaling")) return runScaling(scalingCmd);
    if (app.got_subcommand("plot")) return runPlot(plotCmd);
    if (app.got_subcommand("spd")) return runSpd(spdCmd);
  } catch (const CLI::ValidationError& e) {
    std::cerr << "raycube: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "raycube: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace raycube::host
