#pragma once
// The factory of engines: the one place that knows every engine (threads here; SimGrid and MPI in the
// engines' module, host/engines/engine_module.h).
#include <cstdint>
#include <memory>
#include <vector>

#include "host/machine/machine_engine.h"

namespace raycube::host {

// The engine the settings ask for: threads on shared memory (with the jitter wrapper when asked), or
// SimGrid actors in simulated time (settings.emulate). hypercubeNode: each processor's node on the cube.
template <class Real>
std::unique_ptr<MachineEngine<Real>> makeEngine(const MachineSettings& settings,
                                                const std::vector<std::uint32_t>& hypercubeNode);

}  // namespace raycube::host
