#include "host/machine_engine.h"

#include <stdexcept>

#include "host/mpi_machine.h"
#include "host/mpi_session.h"
#include "host/simulated_machine.h"
#include "host/threaded_machine.h"

namespace raycube::host {

template <class Real>
std::unique_ptr<MachineEngine<Real>> makeEngine(const MachineSettings& settings,
                                                const std::vector<std::uint32_t>& hypercubeNode) {
  if (settings.mpi) {
    if (settings.emulate) throw std::invalid_argument("the MPI engine runs on real ranks, not in simulated time");
    queues::MpiLink* link = hostMpiLink();
    if (link == nullptr) throw std::invalid_argument("the MPI engine runs on rank 0 of mpirun (host/mpi_session.h)");
    return std::make_unique<MpiMachine<Real>>(*link, settings.queueCapacity, settings.rayBatch, settings.jitterSeed);
  }
  if (settings.emulate)
    return std::make_unique<SimulatedMachine<Real>>(*settings.emulate, settings.queueCapacity, hypercubeNode);
  return std::make_unique<ThreadedMachine<Real>>(settings.queueCapacity, settings.jitterSeed);
}

template std::unique_ptr<MachineEngine<float>> makeEngine<float>(const MachineSettings&,
                                                                 const std::vector<std::uint32_t>&);
template std::unique_ptr<MachineEngine<double>> makeEngine<double>(const MachineSettings&,
                                                                   const std::vector<std::uint32_t>&);

}  // namespace raycube::host
