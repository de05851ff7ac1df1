#pragma once
// What raycube's subcommands share (host/cli/): the option maps and validators, the options of a render
// (which a scaling study takes too), and the scene and settings they make.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/precision.h"
#include "core/scene.h"
#include "core/view.h"
#include "host/machine/machine_settings.h"
#include "host/machine/render_settings.h"
#include "node/light_sources.h"
#include "node/region_cells.h"

namespace raycube::host {

// 16x16 is the paper's 256 processors squared; 64x64 leaves room without exhausting threads.
inline constexpr int kMaxProcessorsPerSide = 64;

// The choices of the options that name one, and the values they stand for.
extern const std::map<std::string, RenderMode> kModes;
extern const std::map<std::string, node::LightRayMode> kLightRays;
extern const std::map<std::string, node::CellStructure> kCellStructures;
extern const std::map<std::string, node::FifoFull> kFifoFull;
extern const std::map<std::string, Balance> kBalances;
extern const std::map<std::string, LoadMetric> kLoadMetrics;
extern const std::map<std::string, core::Precision> kPrecisions;
extern const std::map<std::string, core::Sampling> kSamplings;

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
  std::string procs;    // empty: 4x4, or what fits a smaller image
  std::string overlayPath;
  std::string loadChartPath;
  std::string reportPath;
  std::string lightRays = "pyramid";
  std::string cells = "auto";
  std::string fifoFull;  // empty: the engine's own (fifoFullFor)
  std::string balance = "auto";
  std::string loadMetric = "cost";
  std::string emulate;
  std::string platformPath;
  std::string costsPath;
  int ranks = 0;  // --ranks N: emulate an N-rank MPI job on the platform's node-0
  std::string tracePath;
  std::string timelinePath;
  std::string transport = "threads";
  MachineSettings machine;
};

// The machine's options as the command gave them (the processor grid aside).
MachineSettings machineSettingsOf(const RenderCommand& cmd);

// "AxB" with both in [1, limit]; what names the option in the error. Digits only: a number that does not
// fit is an error, never wrapped into range.
std::pair<int, int> parsePair(const std::string& text, const char* what, const char* form, int limit);

// CLI::Range lets NaN through (every comparison with it is false).
extern const CLI::Validator kNotNaN;

// Output files are checked before a render that may take minutes: the extension, and that the file can be
// created (its folder is created as writing would). A file that did not exist is removed again.
// `extensions`: the formats the option writes ("" for any file).
void requireWritable(const std::string& path, const char* option, const std::vector<std::string>& extensions);

// --spd NAME[:SIZE]: a built-in SPD generator and its size (0 for the SPD's default size).
struct SpdChoice {
  std::string name;
  int size = 0;
};

// Throws std::invalid_argument naming the known generators, or the sizes a generator accepts.
SpdChoice parseSpdChoice(const std::string& text);

// Checks NAME[:SIZE] while the command line is parsed, before any work.
extern const CLI::Validator kSpdChoice;

core::Scene loadScene(const RenderCommand& cmd);

// Charts and reports go where the user points, creating the folder as the image outputs do.
std::filesystem::path ensureParent(const std::filesystem::path& path);

RenderSettings renderSettingsOf(const RenderCommand& cmd, const core::Scene& scene);

std::string spdSceneList();

void addSpdOption(CLI::App* app, std::string& spd);

// The options of a render; a scaling study takes the same, but a list of processor counts for --procs.
void addRenderOptions(CLI::App* render, RenderCommand& cmd, bool procsAsGrid);

}  // namespace raycube::host
