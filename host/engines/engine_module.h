#pragma once
// The engines on SimGrid and Open MPI live in a module of their own (raycube_engines.so, beside the program),
// loaded the first time a run asks for one (--emulate, --transport mpi): SimGrid brings ns-3 and Open MPI
// its runtime, 30 libraries whose loading and symbol binding would cost every run a noticeable share,
// though most runs use neither. The module's code is the node code of the program itself (it resolves
// against the program's symbols): one copy of every logical processor, whichever engine drives it.
// Programs linking the engines' objects directly (the tests, the benchmarks) provide them before main.
#include <cstdint>
#include <functional>
#include <memory>
#include <type_traits>
#include <vector>

#include "host/machine/machine_engine.h"

namespace raycube::host {

class EngineModule {
 public:
  virtual ~EngineModule() = default;
  // The engine for settings.emulate (SimGrid) or settings.mpi (rank 0 of mpirun); see makeEngine.
  virtual std::unique_ptr<MachineEngine<float>> makeFloat(
      const MachineSettings& settings, const std::vector<std::uint32_t>& hypercubeNode) const = 0;
  virtual std::unique_ptr<MachineEngine<double>> makeDouble(
      const MachineSettings& settings, const std::vector<std::uint32_t>& hypercubeNode) const = 0;
  // host/engines/mpi/mpi_session.h: starts MPI, runs hostMain on rank 0 and serves renders on the other
  // ranks.
  virtual int runUnderMpi(int argc, char** argv, const std::function<int()>& hostMain) const = 0;
  // Whether this process is rank 0 of mpirun, inside runUnderMpi's hostMain.
  virtual bool hostsMpiRanks() const = 0;

  template <class Real>
  std::unique_ptr<MachineEngine<Real>> make(const MachineSettings& settings,
                                            const std::vector<std::uint32_t>& hypercubeNode) const {
    if constexpr (std::is_same_v<Real, float>)
      return makeFloat(settings, hypercubeNode);
    else
      return makeDouble(settings, hypercubeNode);
  }
};

// Called once by the module (or a program holding the engines' objects) as it starts; `engines` outlives it.
void provideEngineModule(const EngineModule& engines);
// The engines, loading the module if no one provided them; throws std::runtime_error, saying why, if it
// cannot be loaded.
const EngineModule& engineModule();
// Whether this process is rank 0 of mpirun (false while the module is not loaded: then it is not).
bool hostsMpiRanks();

// Whether the command line asks for the MPI engine (--transport mpi): main starts MPI first.
bool asksForMpi(int argc, char** argv);

}  // namespace raycube::host
