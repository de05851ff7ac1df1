#include "host/engines/make_engine.h"

#include "host/engines/engine_module.h"
#include "host/engines/threads/threaded_machine.h"

namespace raycube::host {

template <class Real>
std::unique_ptr<MachineEngine<Real>> makeEngine(const MachineSettings& settings,
                                                const std::vector<std::uint32_t>& hypercubeNode) {
  if (settings.mpi || settings.emulate) return engineModule().make<Real>(settings, hypercubeNode);
  return std::make_unique<ThreadedMachine<Real>>(fifoRaysFor(settings), settings.jitterSeed,
                                                 settings.backlogLimit, settings.stallPeriod,
                                                 settings.loseTheTokenForTests, settings.stallAStepForTests);
}

template std::unique_ptr<MachineEngine<float>> makeEngine<float>(const MachineSettings&,
                                                                 const std::vector<std::uint32_t>&);
template std::unique_ptr<MachineEngine<double>> makeEngine<double>(const MachineSettings&,
                                                                   const std::vector<std::uint32_t>&);

}  // namespace raycube::host
