#pragma once
// The machine over MPI: the same logical processors on the ranks of mpirun, as the paper's processors were
// separate computers with their own memory. Rank 0 is the host (the iPSC's cube manager, 3.2 steps 1-2,
// 3.4): it partitions and prunes as for every engine, sends each rank the context and the setups of its
// processors only (host/engines/machine_wire.h), accumulates the contributions and gathers the reports. Ranks
// 1..N-1 run the processors, P/(N-1) each, on threads over queues/interconnects/mpi_interconnect.h.
#include <chrono>

#include "host/machine/machine_engine.h"
#include "queues/interconnects/mpi_link.h"

namespace raycube::host {

template <class Real>
class MpiMachine final : public MachineEngine<Real> {
 public:
  // stallPeriod, stallAStep, loseTheToken: MachineSettings::stallPeriod, stallAStepForTests and
  // loseTheTokenForTests (the watchdogs and their tests).
  MpiMachine(queues::MpiLink& link, std::size_t queueCapacity, std::size_t rayBatch, unsigned jitterSeed,
             std::chrono::milliseconds stallPeriod = std::chrono::milliseconds(120000),
             bool stallAStep = false, bool loseTheToken = false)
      : link_(link),
        queueCapacity_(queueCapacity),
        rayBatch_(rayBatch),
        jitterSeed_(jitterSeed),
        stallPeriod_(stallPeriod),
        stallAStep_(stallAStep),
        loseTheToken_(loseTheToken) {}
  MachineRun run(const node::MachineContext& context, std::vector<node::NodeSetup> setups,
                 const EngineHooks& hooks) override;

 private:
  queues::MpiLink& link_;
  std::size_t queueCapacity_;
  std::size_t rayBatch_;
  unsigned jitterSeed_;
  std::chrono::milliseconds stallPeriod_;
  bool stallAStep_;
  bool loseTheToken_;
};

// Which rank runs each of `processors` processors: contiguous runs of ids (neighbours in a grid numbered
// row by row stay together), as even as possible; ranks beyond the processor count get none.
std::vector<int> ranksOfProcessors(int processors, int ranks);

// Ranks 1..N-1: run the renders the host sends until it says quit; returns the host's exit status.
int serveMachineJobs(queues::MpiLink& link);

// This process's peak resident memory in bytes (getrusage).
std::uint64_t peakResidentBytes();

}  // namespace raycube::host
