#pragma once
// The machine on threads (the emulator's default engine): one thread per logical processor on the
// shared-memory interconnect (queues/interconnects/shared_memory_interconnect.h); the calling thread is the
// host.
#include <chrono>

#include "host/machine/machine_engine.h"

namespace raycube::host {

template <class Real>
class ThreadedMachine final : public MachineEngine<Real> {
 public:
  // stallPeriod: MachineSettings::stallPeriod; loseTheToken, stallAStep: MachineSettings::
  // loseTheTokenForTests and stallAStepForTests.
  ThreadedMachine(std::size_t queueCapacity, unsigned jitterSeed, std::size_t backlogLimit,
                  std::chrono::milliseconds stallPeriod = std::chrono::milliseconds(120000),
                  bool loseTheToken = false, bool stallAStep = false)
      : queueCapacity_(queueCapacity),
        jitterSeed_(jitterSeed),
        backlogLimit_(backlogLimit),
        stallPeriod_(stallPeriod),
        loseTheToken_(loseTheToken),
        stallAStep_(stallAStep) {}
  MachineRun run(const node::MachineContext& context, std::vector<node::NodeSetup> setups,
                 const EngineHooks& hooks) override;

 private:
  std::size_t queueCapacity_;
  unsigned jitterSeed_;       // > 0: random delays around every transport operation (tests)
  std::size_t backlogLimit_;  // waiting rays that hold primaries back (MachineSettings::backlogLimit)
  std::chrono::milliseconds stallPeriod_;
  bool loseTheToken_;
  bool stallAStep_;
};

}  // namespace raycube::host
