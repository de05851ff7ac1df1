// The module raycube_engines.so (host/engines/engine_module.h): the engines on SimGrid and Open MPI, provided
// to the program as the module is loaded (or, in a program linking these objects, before main).
#include <stdexcept>

#include "host/engines/engine_module.h"
#include "host/engines/mpi/mpi_machine.h"
#include "host/engines/mpi/mpi_session.h"
#include "host/engines/simgrid/emulated_machine.h"

namespace raycube::host {
namespace {

class Engines final : public EngineModule {
 public:
  std::unique_ptr<MachineEngine<float>> makeFloat(
      const MachineSettings& settings, const std::vector<std::uint32_t>& hypercubeNode) const override {
    return makeFor<float>(settings, hypercubeNode);
  }
  std::unique_ptr<MachineEngine<double>> makeDouble(
      const MachineSettings& settings, const std::vector<std::uint32_t>& hypercubeNode) const override {
    return makeFor<double>(settings, hypercubeNode);
  }
  int runUnderMpi(int argc, char** argv, const std::function<int()>& hostMain) const override {
    return host::runUnderMpi(argc, argv, hostMain);
  }
  bool hostsMpiRanks() const override { return hostMpiLink() != nullptr; }

 private:
  template <class Real>
  static std::unique_ptr<MachineEngine<Real>> makeFor(const MachineSettings& settings,
                                                      const std::vector<std::uint32_t>& hypercubeNode) {
    if (settings.mpi) {
      if (settings.emulate)
        throw std::invalid_argument("the MPI engine runs on real ranks, not in simulated time");
      queues::MpiLink* link = hostMpiLink();
      if (link == nullptr)
        throw std::invalid_argument(
            "the MPI engine runs on rank 0 of mpirun (host/engines/mpi/mpi_session.h)");
      return std::make_unique<MpiMachine<Real>>(*link, fifoRaysFor(settings), settings.rayBatch,
                                                settings.jitterSeed, settings.stallPeriod,
                                                settings.stallAStepForTests, settings.loseTheTokenForTests);
    }
    if (!settings.emulate) throw std::invalid_argument("the distributed engines run emulated or over MPI");
    return std::make_unique<EmulatedMachine<Real>>(*settings.emulate, fifoRaysFor(settings), hypercubeNode,
                                                   settings.stallPeriod, settings.stallAStepForTests);
  }
};

const Engines kEngines;
[[maybe_unused]] const bool kProvided = (provideEngineModule(kEngines), true);

}  // namespace
}  // namespace raycube::host
