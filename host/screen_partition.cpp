#include "host/screen_partition.h"

#include <algorithm>
#include <numeric>

#include "host/bsp_partition.h"
#include "host/machine_checks.h"

namespace raycube::host {
namespace {

// 3.1: pixel areas with (nearly) equal sample counts.
std::vector<int> evenCuts(int samples, int parts) {
  std::vector<int> cuts;
  for (int k = 0; k <= parts; ++k) cuts.push_back(int((long long)samples * k / parts));
  return cuts;
}

ScreenPartition uniformGrid(const core::View& view, const MachineSettings& machine) {
  return {node::RegionMap::grid(evenCuts(view.samplesX(), machine.columns),
                                evenCuts(view.samplesY(), machine.rows), node::ScreenLines(view)),
          Balance::Uniform, std::nullopt, std::nullopt};
}

ScreenPartition equalLoads(const core::View& view, const LoadSample& load, const MachineSettings& machine) {
  return {node::RegionMap(bspPartition(view.samplesX(), view.samplesY(), machine.rows * machine.columns, load,
                                       machine.loadMetric),
                          node::ScreenLines(view)),
          Balance::Bsp, std::nullopt, std::nullopt};
}

}  // namespace

double estimatedSpan(const std::vector<double>& loads, int cores) {
  if (loads.empty()) return 0;
  const double total = std::accumulate(loads.begin(), loads.end(), 0.0);
  return std::max(total / std::max(1, cores), *std::max_element(loads.begin(), loads.end()));
}

ScreenPartition partitionScreen(const core::View& view, const LoadSample& load,
                                const MachineSettings& machine, int cores) {
  const PartitionsFitting fits = partitionsFitting(machine, view);
  if (machine.balance == Balance::Bsp || (machine.balance == Balance::Auto && !fits.grid))
    return equalLoads(view, load, machine);
  if (machine.balance == Balance::Uniform || !fits.bsp()) return uniformGrid(view, machine);
  ScreenPartition balanced = equalLoads(view, load, machine), grid = uniformGrid(view, machine);
  for (ScreenPartition* p : {&balanced, &grid})
    p->estimates = estimateAreas(p->regions.areas(), load, machine.loadMetric);
  const PartitionForecast forecast{cores, estimatedSpan(balanced.estimates->loads, cores),
                                   estimatedSpan(grid.estimates->loads, cores)};
  ScreenPartition& made = forecast.uniformSpan < forecast.bspSpan ? grid : balanced;
  made.forecast = forecast;
  return std::move(made);
}

}  // namespace raycube::host
