#include "host/cli/options.h"

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "core/spd/generators.h"
#include "host/machine/emulated_platform.h"

namespace raycube::host {

const std::map<std::string, RenderMode> kModes{{"reference", RenderMode::Reference},
                                               {"image-parallel", RenderMode::ImageParallel},
                                               {"machine", RenderMode::Machine}};
const std::map<std::string, node::LightRayMode> kLightRays{{"messages", node::LightRayMode::Messages},
                                                           {"cone", node::LightRayMode::Cone},
                                                           {"pyramid", node::LightRayMode::Pyramid}};
const std::map<std::string, node::CellStructure> kCellStructures{{"auto", node::CellStructure::Auto},
                                                                 {"paper", node::CellStructure::Paper},
                                                                 {"bvh", node::CellStructure::Bvh}};
const std::map<std::string, node::FifoFull> kFifoFull{{"overflow", node::FifoFull::Overflow},
                                                      {"lock", node::FifoFull::Lock}};
const std::map<std::string, Balance> kBalances{
    {"auto", Balance::Auto}, {"uniform", Balance::Uniform}, {"bsp", Balance::Bsp}};
const std::map<std::string, LoadMetric> kLoadMetrics{{"rays", LoadMetric::Rays}, {"cost", LoadMetric::Cost}};
const std::map<std::string, core::Precision> kPrecisions{{"float", core::Precision::Float},
                                                         {"double", core::Precision::Double}};
const std::map<std::string, core::Sampling> kSamplings{{"centers", core::Sampling::Centers},
                                                       {"corners", core::Sampling::Corners}};

namespace {

// --emulate NAME | --platform FILE.xml, with --costs FILE: the machine to simulate, if any.
std::optional<EmulatedPlatform> emulatedPlatform(const RenderCommand& cmd) {
  std::optional<EmulatedPlatform> platform;
  if (!cmd.platformPath.empty()) {
    platform = userPlatform(cmd.platformPath, cmd.costsPath);
  } else if (!cmd.emulate.empty()) {
    platform = builtinPlatform(cmd.emulate);
    if (!cmd.costsPath.empty()) applyCostFile(cmd.costsPath, *platform);
  } else {
    if (!cmd.costsPath.empty()) throw std::invalid_argument("--costs needs --emulate or --platform");
    if (cmd.ranks > 0) throw std::invalid_argument("--ranks needs --emulate or --platform");
    return std::nullopt;
  }
  platform->ranks = cmd.ranks;
  return platform;
}

}  // namespace

MachineSettings machineSettingsOf(const RenderCommand& cmd) {
  MachineSettings machine = cmd.machine;
  machine.lightRays = kLightRays.at(cmd.lightRays);
  machine.cells = kCellStructures.at(cmd.cells);
  if (!cmd.fifoFull.empty()) machine.fifoFull = kFifoFull.at(cmd.fifoFull);
  machine.balance = kBalances.at(cmd.balance);
  machine.loadMetric = kLoadMetrics.at(cmd.loadMetric);
  machine.emulate = emulatedPlatform(cmd);
  machine.mpi = cmd.transport == "mpi";
  return machine;
}

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
      if (CLI::detail::lexical_cast(text, value) && std::isnan(value))
        return std::string("NaN is not a number");
      return std::string();
    },
    "", "NOT_NAN");

void requireWritable(const std::string& path, const char* option,
                     const std::vector<std::string>& extensions) {
  if (path.empty()) return;
  const std::filesystem::path p(path);
  if (!extensions.empty()) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
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
      throw CLI::ValidationError(option,
                                 fmt::format("cannot write '{}': {}", path,
                                             std::error_code(errno, std::generic_category()).message()));
  }
  if (!existed) std::filesystem::remove(p, error);
}

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
    throw std::invalid_argument(
        fmt::format("{} size must be a whole number from 1 to {} (default {}), got '{}'", generator.name,
                    generator.maxSize, generator.defaultSize, digits));
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

std::filesystem::path ensureParent(const std::filesystem::path& path) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  return path;
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

namespace {

// The scene: a file, or a built-in one; and the image size.
void addSceneOptions(CLI::App* render, RenderCommand& cmd) {
  render->add_option("scene", cmd.scenePath, "NFF scene file (default: the built-in balls scene)")
      ->check(CLI::ExistingFile);
  render
      ->add_option("--balls", cmd.balls,
                   "Built-in SPD balls (sphereflake) scene of this size (1-6): --spd balls:N")
      ->check(CLI::Range(1, core::kMaxBallsSize));
  addSpdOption(render, cmd.spd);
  render->add_option("--size", cmd.size, "Image size WxH (overrides the file's resolution)");
}

// How rays are traced, whatever the mode: depth, samples, precision (section 3.4).
void addTracingOptions(CLI::App* render, RenderCommand& cmd) {
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
}

// The machine's own: FIFOs, cells, light rays, partitioning and its load estimate (sections 3.1-3.7).
void addMachineOptions(CLI::App* render, RenderCommand& cmd) {
  render
      ->add_option_function<std::size_t>(
          "--queue-capacity", [&cmd](const std::size_t& rays) { cmd.machine.queueCapacity = rays; },
          "Rays per face FIFO: 512 on threads; the iPSC's 128 in emulated time and over MPI")
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 20));
  render
      ->add_option("--fifo-full", cmd.fifoFull,
                   "What a send into a full FIFO does: overflow (the ray waits in a list while the processor "
                   "goes on consuming; the default) | lock (3.5.2: the synthesis task locks until the FIFO "
                   "has room; a cycle of full FIFOs is a deadlock, reported with exit code 4). Threads and "
                   "emulated machines")
      ->transform(CLI::IsMember(keysOf(kFifoFull), CLI::ignore_case));
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
                   "Load estimate: one sub-sampled pixel per WxW window; auto: from the resolution and the "
                   "processors (the least predicted end-to-end time, host/prepare/load_estimate.h)")
      ->transform(CLI::Transformer(std::map<std::string, std::string>{{"auto", std::to_string(kAutoWindow)}},
                                   CLI::ignore_case))
      ->check(CLI::Range(kAutoWindow, 1024));
}

// What drives the machine: threads, SimGrid in simulated time, or MPI ranks.
void addEngineOptions(CLI::App* render, RenderCommand& cmd) {
  render
      ->add_option("--emulate", cmd.emulate,
                   "Run the machine on SimGrid in simulated time: ipsc1 (the paper's iPSC/1) | cluster")
      ->check(CLI::IsMember({"ipsc1", "cluster"}));
  render
      ->add_option("--transport", cmd.transport,
                   "threads (shared-memory FIFOs) | mpi (under mpirun -np N: rank 0 the host, ranks 1..N-1 "
                   "the processors; README, The machine over MPI)")
      ->check(CLI::IsMember({"threads", "mpi"}));
  render->add_option("--ray-batch", cmd.machine.rayBatch, "MPI: rays per message to one rank, at most")
      ->check(CLI::Range(std::size_t(1), std::size_t(4096)));
  render->add_option("--platform", cmd.platformPath,
                     "A SimGrid platform XML to emulate (hosts node-0 ... and manager; see README)");
  render->add_option("--costs", cmd.costsPath,
                     "Cost table: 'name value' lines (README, Emulated machine time)");
  render
      ->add_option("--ranks", cmd.ranks,
                   "Emulated: the run as an N-rank MPI job on one computer (the platform's node-0, its cores "
                   "shared by every processor and the host), as mpirun -np N on this machine")
      ->check(CLI::Range(2, 4096));
}

// What a run writes besides the image: statistics, charts, traces, a report.
void addOutputOptions(CLI::App* render, RenderCommand& cmd) {
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
}

}  // namespace

void addRenderOptions(CLI::App* render, RenderCommand& cmd, bool procsAsGrid) {
  addSceneOptions(render, cmd);
  addTracingOptions(render, cmd);
  if (procsAsGrid)
    render->add_option("--procs", cmd.procs,
                       "Logical processors as RxC (rows x columns), default 4x4; with --balance bsp only R*C "
                       "counts (at most 1024), with auto R x C is the grid it weighs against the BSP");
  addMachineOptions(render, cmd);
  addEngineOptions(render, cmd);
  addOutputOptions(render, cmd);
  render->get_option("--balls")->excludes("scene");
  render->get_option("--spd")->excludes("scene")->excludes("--balls");
}

}  // namespace raycube::host
