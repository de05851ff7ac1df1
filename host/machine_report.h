#pragma once
// What the machine measured, per processor: the compact table of the summary, the JSON of --stats, and a
// picture (--overlay): the image with region borders and each region tinted by its load.
#include <string>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "host/machine.h"

namespace raycube::host {

std::string machineTable(const MachineReport& report);
nlohmann::json machineJson(const MachineReport& report);
// Region borders in white; each region darkened in proportion to (1 - its load / the largest load), and a
// bar along its top edge as long as its share of the largest load. Load = ray segments processed.
core::Image loadOverlay(const core::Image& image, const MachineReport& report, bool cornerSampling);

}  // namespace raycube::host
