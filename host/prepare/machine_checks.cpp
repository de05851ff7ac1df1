#include "host/prepare/machine_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "host/prepare/hypercube_mapping.h"

namespace raycube::host {

PartitionsFitting partitionsFitting(const MachineSettings& machine, const core::View& view) {
  const long long processors = (long long)machine.rows * machine.columns;
  const bool some = machine.columns >= 1 && machine.rows >= 1;
  PartitionsFitting fits;
  fits.grid = some && machine.columns <= view.samplesX() && machine.rows <= view.samplesY();
  fits.bspSamples = some && processors <= (long long)view.samplesX() * view.samplesY();
  fits.bspMapped = processors <= kMaxMappedVertices;
  return fits;
}

void requireMachineFits(const MachineSettings& machine, const core::View& view) {
  const PartitionsFitting fits = partitionsFitting(machine, view);
  const long long processors = (long long)machine.rows * machine.columns;
  const bool samplesFit = machine.balance == Balance::Bsp       ? fits.bspSamples
                          : machine.balance == Balance::Uniform ? fits.grid
                                                                : fits.grid || fits.bspSamples;
  if (!samplesFit)
    throw std::invalid_argument(
        fmt::format("--procs {}x{}: every processor needs at least one sample (and, on a "
                    "uniform grid, one sample row and column) of the {}x{} sample grid",
                    machine.rows, machine.columns, view.samplesX(), view.samplesY()));
  const bool mappingFits = machine.balance == Balance::Bsp    ? fits.bspMapped
                           : machine.balance == Balance::Auto ? fits.grid || fits.bspMapped
                                                              : true;
  if (!mappingFits)
    throw std::invalid_argument(
        fmt::format("--procs {}x{}: --balance bsp maps at most {} processors onto the hypercube, got {} "
                    "(use fewer processors or --balance uniform)",
                    machine.rows, machine.columns, kMaxMappedVertices, processors));
  if (machine.queueCapacity && *machine.queueCapacity < 1)
    throw std::invalid_argument("--queue-capacity must be at least 1");
  if (machine.subsampleWindow < 1 && machine.subsampleWindow != kAutoWindow)
    throw std::invalid_argument("--subsample must be at least 1, or auto");
}

std::pair<int, int> defaultProcessorGrid(const core::View& view) {
  const MachineSettings defaults;
  return {std::min(defaults.rows, view.samplesY()), std::min(defaults.columns, view.samplesX())};
}

}  // namespace raycube::host
