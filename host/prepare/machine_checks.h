#pragma once
// What a machine run needs of its settings, checked before any work: a user who asks for more processors
// than the image or the hypercube mapping can take learns it at once, not after the preprocessing.
#include <utility>

#include "core/view.h"
#include "host/machine/machine_settings.h"

namespace raycube::host {

// Which partitions can cut this view for these processors: the uniform grid (a sample row and column
// each), the BSP (a sample each, and no more regions than the hypercube mapping places).
struct PartitionsFitting {
  bool grid = false, bspSamples = false, bspMapped = false;
  bool bsp() const { return bspSamples && bspMapped; }
};
PartitionsFitting partitionsFitting(const MachineSettings& machine, const core::View& view);

// Throws std::invalid_argument, naming the option at fault, when the settings cannot run on this view: a
// processor without a sample (or, on a uniform grid, without a sample row or column), more BSP regions
// than the hypercube mapping places (kMaxMappedVertices), a FIFO or sub-sampling window below 1. With
// Balance::Auto, only when neither partition fits.
void requireMachineFits(const MachineSettings& machine, const core::View& view);

// The default processor grid, 4x4, shrunk to what the view's sample grid can hold (a 1x1 image gets 1x1).
std::pair<int, int> defaultProcessorGrid(const core::View& view);

}  // namespace raycube::host
