#pragma once
// `raycube tradeoff`: what each speed/accuracy knob buys and costs. A converged reference (depth 16, many
// rays per pixel, no cut-off) is rendered first; then each knob is swept with the others at their SPD
// defaults, and every setting is timed (median of several renders) and compared with the reference.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "core/trace_stats.h"
#include "host/chart/chart.h"
#include "host/machine/render_settings.h"

namespace raycube::host {

struct TradeoffRow {
  std::string knob;     // "depth", "min-weight", "spp", "precision"
  std::string setting;  // its value
  double seconds = 0;   // whole render, median
  core::TraceCounters counters;
  double rmse = 0, psnr = 0, maxAbs = 0;  // against the converged reference, linear RGB
};

struct TradeoffOptions {
  int runs = 3;  // renders per setting; the median time is reported
  int referenceDepth = 16;
  int referenceRaysPerSample = 64;
};

// Renders with the image-parallel renderer (bit-identical to every other mode). `progress` hears each
// finished setting.
std::vector<TradeoffRow> measureTradeoff(const core::Scene& scene, const RenderSettings& base,
                                         const TradeoffOptions& options,
                                         const std::function<void(const TradeoffRow&)>& progress);

std::string tradeoffTable(const std::vector<TradeoffRow>& rows);

// The load-estimate knob (3.7.1): the machine's sub-sampling window against the preprocessing it costs and
// the balance it buys (BSP, cost metric, `processors` logical processors).
struct SubsampleRow {
  int window = 0;
  double preprocessSeconds = 0;  // median
  double raysMaxOverMean = 0, raysMinOverMean = 0, costMaxOverMean = 0;
};
std::vector<SubsampleRow> measureSubsampling(const core::Scene& scene, const RenderSettings& base,
                                             int processors, int runs);
std::string subsampleTable(const std::vector<SubsampleRow>& rows);
void writeTradeoffCsv(const std::vector<TradeoffRow>& rows, const std::filesystem::path& path);
// The rows an earlier writeTradeoffCsv wrote (intersection and box tests are not in the CSV), to redraw
// the plot without measuring again. Throws std::runtime_error naming path:line on a malformed line.
std::vector<TradeoffRow> readTradeoffCsv(const std::filesystem::path& path);
// Error (RMSE) against time, both on log scales: one named curve per knob, each point labelled with its
// setting.
LineChart tradeoffPlot(const std::vector<TradeoffRow>& rows, std::string caption = "");
inline const char* const kKnobs[] = {"depth", "min-weight", "spp", "precision"};

}  // namespace raycube::host
