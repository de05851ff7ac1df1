#pragma once
// How the host runs the logical processors it has set up (Priol & Bouatouch 3.2 steps 2-3, 3.5): threads
// on shared-memory FIFOs, SimGrid actors in simulated time, MPI ranks. The host hands over the shared
// context and one setup per processor; the engine builds the nodes (each subdivides its own region),
// starts the synthesis phase, hands every contribution to the host's sink until the token ring has proved
// termination, and returns every processor's counts. An engine is new files under host/engines/ and
// one line in makeEngine (host/engines/make_engine.h): renderMachine stays as is.
#include <functional>
#include <memory>
#include <vector>

#include "core/contribution_sink.h"
#include "host/machine/host_work.h"
#include "host/machine/machine_report.h"
#include "node/logical_processor.h"

namespace raycube::host {

struct EngineHooks {
  core::ContributionSink* host = nullptr;  // the host's accumulation: called from one thread at a time
  std::function<void()> synthesisStarts;   // every node has subdivided its region: preprocessing ends
  // Ray segments each processor has evaluated so far, in processor order (progress): called now and then
  // by the host's loop while tracing.
  std::function<void(const std::vector<std::uint64_t>& segmentsEvaluated)> progress;
  // What the host did before handing over (3.2 steps 1-2, 3.7.1): an engine with a clock charges it.
  const HostWork* hostWork = nullptr;
};

struct MachineRun {
  std::vector<ProcessorReport> processors;
  std::optional<EmulatedRun> emulated;  // engines with a clock of their own
  std::optional<MpiRun> mpi;            // engines spread over processes
  // node::FifoFull::Lock: the cycle of locked processors the run stopped on (the counts are up to it).
  std::optional<Deadlock> deadlock;
};

template <class Real>
class MachineEngine {
 public:
  virtual ~MachineEngine() = default;
  virtual MachineRun run(const node::MachineContext& context, std::vector<node::NodeSetup> setups,
                         const EngineHooks& hooks) = 0;
};

}  // namespace raycube::host
