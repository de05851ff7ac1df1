#pragma once
// What the host process did before the synthesis (Priol & Bouatouch 3.2 steps 1-2, 3.7.1), counted by the
// code that did it, so that an emulated machine can charge it to its host in simulated time: the
// sub-sampled rays, the BSP's cuts, the pruning, the mapping onto the hypercube. The transfer of each
// node's setup is counted by the engine, which knows its bytes on the wire.
#include <cstdint>

#include "node/logical_processor.h"

namespace raycube::host {

struct HostWork {
  // 3.7.1 step 1: the sub-sampled pixels' ray trees, counted as a node counts the rays it evaluates (each
  // ray taken up, spawned and finished once, its tests and BVH steps), so one cost table prices both.
  node::NodeStats sampling;
  // 3.7.1 step 2: segment pieces the BSP weighed against candidate lines or clipped to a side (0: a grid).
  std::uint64_t piecesWeighed = 0;
  // 3.2 step 1, 3.7.2: objects examined against regions (every object against every region, and with
  // light volumes every object against every region's volume for each light).
  std::uint64_t regionTests = 0;
  // 3.7.1: steps of the embedding into the hypercube (a node's hops weighed for a vertex).
  std::uint64_t mappingSteps = 0;
};

}  // namespace raycube::host
