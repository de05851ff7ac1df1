#pragma once
// Phase 2 (Priol & Bouatouch 3.1, 3.7.1): the screen cut into the processors' pixel areas. The uniform R x C
// grid of 3.1, the BSP of equal estimated loads of 3.7.1, or, by default, whichever of the two the
// sub-sampled estimate says finishes first on the cores the processors share.
//
// The BSP evens the processors' loads, and pays for it in messages: each cut through a dense part of the
// image splits the rays crossing it, and a split ray is a message and a walk set-up more. Where every
// processor has a CPU of its own (the iPSC, its emulation, MPI ranks), the busiest processor sets the pace
// and the BSP wins. Where 16 or 64 processors share a few cores (threads), the cores set it, busy whatever
// the balance, and the partition making fewer messages wins, often the grid.
#include <optional>

#include "core/view.h"
#include "host/machine/machine_settings.h"
#include "host/prepare/load_estimate.h"
#include "node/region_map.h"

namespace raycube::host {

struct ScreenPartition {
  node::RegionMap regions;
  Balance balance = Balance::Bsp;             // the partition made: Uniform or Bsp
  std::optional<PartitionForecast> forecast;  // what chose it, when Auto had both to choose from
  AreaEstimates estimates;                    // the sub-sample's in each area (and the forecast's loads)
  std::uint64_t piecesWeighed = 0;            // the BSP's work, made or only forecast (HostWork)
};

// The estimated span of areas whose loads are `loads`, on `cores` cores.
double estimatedSpan(const std::vector<double>& loads, int cores);

// `cores`: how many the processors share (Auto's forecast). Auto falls back to the one partition that fits
// the view (machine_checks.h) where only one does; a tie keeps the paper's BSP (spans equal but for
// rounding: the same pieces summed in another order).
ScreenPartition partitionScreen(const core::View& view, const LoadSample& load,
                                const MachineSettings& machine, int cores);

}  // namespace raycube::host
