#pragma once
// What the machine measured, per processor: the compact table of the summary, the JSON of --stats, and a
// picture (--overlay): the image with region borders and each region tinted by its load.
#include <nlohmann/json.hpp>
#include <string>

#include "core/image.h"
#include "host/machine.h"

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
// Region borders in white; each region darkened in proportion to (1 - its load / the largest load), and a
// bar along its top edge as long as its share of the largest load. Load = ray segments processed.
core::Image loadOverlay(const core::Image& image, const MachineReport& report);

}  // namespace raycube::host
