#pragma once
// The machine in simulated time, on SimGrid (S4U): every logical processor runs the same node code as the
// threaded machine, as an actor on its hypercube node's host; the host (the iPSC's cube manager) is an
// actor too. Compute is charged from the work each step counted (EmulatedPlatform's cost table), never
// from a clock, so the simulated time is the same on every run. SimGrid allows one simulation per
// process: each run happens in a child process that streams contributions and reports back.
#include <chrono>

#include "host/machine/emulated_platform.h"
#include "host/machine/machine_engine.h"

namespace raycube::host {

template <class Real>
class EmulatedMachine final : public MachineEngine<Real> {
 public:
  // stallPeriod: MachineSettings::stallPeriod, in wall-clock time (a step that does not end stops the
  // simulated clock too); stallAStep: MachineSettings::stallAStepForTests.
  EmulatedMachine(EmulatedPlatform platform, std::size_t queueCapacity, std::vector<std::uint32_t> cubeNode,
                  std::chrono::milliseconds stallPeriod = std::chrono::milliseconds(120000),
                  bool stallAStep = false)
      : platform_(std::move(platform)),
        queueCapacity_(queueCapacity),
        cubeNode_(std::move(cubeNode)),
        stallPeriod_(stallPeriod),
        stallAStep_(stallAStep) {}
  MachineRun run(const node::MachineContext& context, std::vector<node::NodeSetup> setups,
                 const EngineHooks& hooks) override;

 private:
  EmulatedPlatform platform_;
  std::size_t queueCapacity_;
  std::vector<std::uint32_t> cubeNode_;
  std::chrono::milliseconds stallPeriod_;
  bool stallAStep_;
};

}  // namespace raycube::host
