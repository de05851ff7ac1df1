#include "host/prepare/screen_partition.h"

#include <algorithm>
#include <future>
#include <numeric>

#include "host/prepare/bsp_partition.h"
#include "host/prepare/machine_checks.h"

namespace raycube::host {
namespace {

// Two spans this close are equal: where no ray crosses a cut (tree 11, tetra 6: no secondary rays), both
// partitions hold the same pieces, summed in another order, and differ only in their last bits.
constexpr double kSpansEqualWithin = 1e-9;

// 3.1: pixel areas with (nearly) equal sample counts.
std::vector<int> evenCuts(int samples, int parts) {
  std::vector<int> cuts;
  for (int k = 0; k <= parts; ++k) cuts.push_back(int((long long)samples * k / parts));
  return cuts;
}

// The areas of a partition, and which it is.
struct Areas {
  std::vector<node::SampleRect> areas;
  Balance balance;
  std::uint64_t piecesWeighed = 0;  // the BSP's work
};

Areas uniformGrid(const core::View& view, const MachineSettings& machine) {
  return {node::RegionMap::gridAreas(evenCuts(view.samplesX(), machine.columns),
                                     evenCuts(view.samplesY(), machine.rows)),
          Balance::Uniform};
}

Areas equalLoads(const core::View& view, const LoadSample& load, const MachineSettings& machine) {
  Areas made{{}, Balance::Bsp};
  made.areas = bspPartition(view.samplesX(), view.samplesY(), machine.rows * machine.columns, load,
                            machine.loadMetric, 0, &made.piecesWeighed);
  return made;
}

// The partition of these areas, with what the sub-sample puts in each.
ScreenPartition madeOf(Areas made, AreaEstimates estimates, const core::View& view,
                       const MachineSettings& machine) {
  const int gridColumns = made.balance == Balance::Uniform ? machine.columns : 0;
  return {node::RegionMap(std::move(made.areas), node::ScreenLines(view), gridColumns), made.balance,
          std::nullopt, std::move(estimates), made.piecesWeighed};
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
  auto weighed = [&](Areas areas) {
    AreaEstimates estimates = estimateAreas(areas.areas, load, machine.loadMetric);
    return madeOf(std::move(areas), std::move(estimates), view, machine);
  };
  if (machine.balance == Balance::Bsp || (machine.balance == Balance::Auto && !fits.grid))
    return weighed(equalLoads(view, load, machine));
  if (machine.balance == Balance::Uniform || !fits.bsp()) return weighed(uniformGrid(view, machine));
  // Only the partition made gets its region map: its table of every sample's owner is 128 fresh pages at
  // 512 x 512.
  // The grid weighed on another core while the BSP cuts.
  Areas grid = uniformGrid(view, machine);
  std::future<AreaEstimates> weighingGrid =
      std::async(std::launch::async, [&] { return estimateAreas(grid.areas, load, machine.loadMetric); });
  Areas balanced = equalLoads(view, load, machine);
  AreaEstimates balancedLoads = estimateAreas(balanced.areas, load, machine.loadMetric);
  AreaEstimates gridLoads = weighingGrid.get();
  const PartitionForecast forecast{cores, estimatedSpan(balancedLoads.loads, cores),
                                   estimatedSpan(gridLoads.loads, cores)};
  const bool gridWins = forecast.uniformSpan < forecast.bspSpan * (1 - kSpansEqualWithin);
  const std::uint64_t piecesWeighed = balanced.piecesWeighed;
  ScreenPartition made = madeOf(gridWins ? std::move(grid) : std::move(balanced),
                                gridWins ? std::move(gridLoads) : std::move(balancedLoads), view, machine);
  made.forecast = forecast;
  made.piecesWeighed = piecesWeighed;
  return made;
}

}  // namespace raycube::host
