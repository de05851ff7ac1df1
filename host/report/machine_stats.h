#pragma once
// What the machine measured, per processor: the compact table of the summary, the JSON of --stats, and a
// picture (--overlay): the image with its regions numbered and tinted by their load.
#include <nlohmann/json.hpp>
#include <string>

#include "core/image.h"
#include "host/chart/chart.h"
#include "host/machine/machine_report.h"

namespace raycube::host {

// Figure 15 and the balance it achieves: per processor the estimated and the actual load (rays processed,
// and their cost: intersection tests + cell steps), each normalised to its mean.
struct LoadBalance {
  std::vector<double> estimated, actualRays, actualCost;  // normalised to mean 1
  double raysMaxOverMean = 0, raysMinOverMean = 0, costMaxOverMean = 0, costMinOverMean = 0;
  // The actual load the estimate is compared with (figure 15: rays processed), and the correlation.
  std::vector<double> actualInMetric;
  double pearson = 0;
};
LoadBalance loadBalanceOf(const MachineReport& report);

std::string machineTable(const MachineReport& report);
nlohmann::json machineJson(const MachineReport& report);
// "uniform 4x4 grid" or "BSP of 16 areas (cost metric, sub-sampling 8x8)": how the screen was cut.
std::string partitionName(const MachineReport& report);
// The image with each processor's region outlined, numbered, and tinted by the rays it processed on a
// colour scale beside the picture (--overlay).
ImageChart loadOverlay(const core::Image& image, const MachineReport& report, std::string caption = "");

}  // namespace raycube::host
