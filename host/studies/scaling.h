#pragma once
// A scaling study in simulated time (Priol & Bouatouch table 2): the same render on several processor
// counts of an emulated machine, with speedup and efficiency against the smallest count.
#include <filesystem>
#include <string>
#include <vector>

#include "host/chart/chart.h"
#include "host/machine/machine_settings.h"
#include "host/machine/render_settings.h"

namespace raycube::host {

struct ScalingPoint {
  int processors = 0;
  int rows = 0, columns = 0;
  double makespan = 0;   // simulated seconds
  double nodeSpeed = 0;  // the emulated node-0's speed, flop-equivalents per second
  double speedup = 0;    // against the smallest count, scaled by it (so 1 processor gives 1)
  double efficiency = 0;
  double blockedShare = 0;  // of processor-time, waiting on full FIFOs
  std::uint64_t rayMessages = 0;
  double wallSeconds = 0;
  // --fifo-full lock: the simulated instant the run deadlocked (host/machine/deadlock.h), -1 when it
  // completed; makespan, speedup and efficiency are then NaN.
  double deadlockAt = -1;
  // The host's preparation before the synthesis (HostPreprocessing), and both together: the end-to-end
  // time, its speedup and efficiency against the smallest count's synthesis alone (one processor needs no
  // partition: its time is the sequential work).
  double preprocessing = 0, endToEnd = 0;
  double endToEndSpeedup = 0, endToEndEfficiency = 0;
};

// The grid closest to square with rows x columns == processors (rows <= columns).
std::pair<int, int> nearSquareGrid(int processors);
std::vector<ScalingPoint> scalingStudy(const core::Scene& scene, const RenderSettings& settings,
                                       MachineSettings machine, std::vector<int> processors);
// The table, with table 2's published times beside ours for the paper's configuration.
std::string scalingTable(const std::vector<ScalingPoint>& points, const core::Scene& scene,
                         const RenderSettings& settings);
// Speed-up against processors (both log), each point labelled with its efficiency, beside the ideal; on
// the iPSC/1 in table 2's configuration, the paper's published speed-ups as a curve of their own.
LineChart scalingPlot(const std::vector<ScalingPoint>& points, const core::Scene& scene,
                      const RenderSettings& settings, const std::string& platform);
void writeScalingCsv(const std::vector<ScalingPoint>& points, const std::filesystem::path& path);

}  // namespace raycube::host
