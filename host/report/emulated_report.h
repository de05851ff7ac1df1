#pragma once
// What a run in simulated time reports (the SimGrid engine): the emulated machine's clock per processor,
// traffic per link, and the timeline as a trace a standard viewer opens.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "host/chart/chart.h"
#include "host/machine/machine_report.h"

namespace raycube::host {

// Share of the processors' time (makespan x processors) spent blocked on full FIFOs (3.6's "locked").
double blockedShare(const MachineReport& report);
// 3.7's saturation as it evolves: per tenth of the makespan, the share of the processors' time spent
// blocked (locked on a full FIFO under --fifo-full lock), from the timeline.
std::vector<double> blockedShareByTenth(const MachineReport& report);
std::string emulatedTable(const MachineReport& report);
nlohmann::json emulatedJson(const MachineReport& report);
// Chrome trace-event JSON (Perfetto, chrome://tracing): one track per processor, one slice per state.
void writeChromeTrace(const MachineReport& report, const std::filesystem::path& path);
// The same as a chart: one row per processor, coloured by state (the picture of saturation spreading).
TimelineChart timelineChart(const MachineReport& report, const std::string& caption);

}  // namespace raycube::host
