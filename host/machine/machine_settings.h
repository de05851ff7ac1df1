#pragma once
// What a user asks of the message-passing machine (Priol & Bouatouch section 3): how many processors, how
// the screen is partitioned among them (3.1, 3.7.1), their FIFOs (3.5.2), cells (3.3) and light rays
// (3.7.2), and which engine drives them.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "host/machine/emulated_platform.h"
#include "node/logical_processor.h"
#include "node/scheduling.h"
#include "queues/spsc_queue.h"

namespace raycube::host {

// The load the sub-sampled estimate measures and the BSP balances (3.7.1).
enum class LoadMetric : std::uint8_t {
  Rays,  // the paper's: every ray (every piece of a split ray) counts one
  Cost,  // refined: a ray weighs one plus a share of the traversal steps and intersection tests its
         // sub-sampled twin cost (relative to the mean); every piece of a split ray weighs the one whole
         // (its message and walk set-up, as in the ray metric) and the share by its projected length
};

enum class Balance : std::uint8_t {
  Auto,     // whichever of the two the sub-sampled estimate says finishes first
            // (host/prepare/screen_partition.h)
  Uniform,  // 3.1: an R x C grid of equal pixel areas
  Bsp,      // 3.7.1: a BSP of the screen into areas of equal estimated load
};

// What chose Balance::Auto's partition: the estimated span of each, in the load metric (the sub-sampled
// loads scaled to the image): the busiest processor's load or the whole load over the cores the processors
// share, whichever is longer.
struct PartitionForecast {
  int cores = 0;
  double bspSpan = 0, uniformSpan = 0;
};

// MachineSettings::subsampleWindow: chosen from the resolution and the processors (subsampleWindowFor).
inline constexpr int kAutoWindow = 0;

struct MachineSettings {
  int rows = 4;
  int columns = 4;
  Balance balance = Balance::Auto;  // with Bsp only rows x columns (the processor count) matters
  int subsampleWindow = 8;  // 3.7.1: one sub-sampled pixel per w x w window; kAutoWindow: from the resolution
  LoadMetric loadMetric = LoadMetric::Cost;
  // Rays per face FIFO (3.5.2); none: the engine's own (fifoRaysFor).
  std::optional<std::size_t> queueCapacity;
  // What a send into a full FIFO does (3.5.2); none: the engine's own (fifoFullFor).
  std::optional<node::FifoFull> fifoFull;
  // How each region holds its objects; Auto: the engine's own (cellsFor).
  node::CellStructure cells = node::CellStructure::Auto;
  int cellLevel = 2;  // recursive halvings of each pixel area into super-cells (3.3)
  node::LightRayMode lightRays = node::LightRayMode::Pyramid;  // 3.7.2
  unsigned jitterSeed = 0;  // tests: > 0 injects random delays around every transport operation
  // The engines' watchdog (host/engines/stall_watch.h): a machine in which no processor finished a ray or
  // moved a message for this long has stalled, an error. Far beyond any step of a legitimate run (one
  // primary ray's local ray tree: milliseconds, seconds under the sanitizers); tests shorten it.
  std::chrono::milliseconds stallPeriod{120000};
  // Tests of the watchdog: the processor that would pass the termination token drops it instead.
  bool loseTheTokenForTests = false;
  // Tests of the watchdog: the last processor never returns from the step that sends its first contribution
  // (queues/interconnects/step_stalling_transport.h).
  bool stallAStepForTests = false;
  // Threads: rays waiting for room machine-wide from which no primary ray is shot (node::scheduling::
  // kMachineBacklogLimit); tests lower it to hold primaries back often.
  std::size_t backlogLimit = node::scheduling::kMachineBacklogLimit;
  std::optional<EmulatedPlatform> emulate;  // set: run on SimGrid in that machine's simulated time
  bool mpi =
      false;  // run the processors on the other ranks of MPI_COMM_WORLD (host/engines/mpi/mpi_machine.h)
  std::size_t rayBatch = 16;  // MPI: rays per message to one rank, at most
  // Embed the regions in the hypercube (3.7.1) for the report, during the synthesis, when not emulating; the
  // emulated machine always does, its links need it. Off by default: the BSP's heuristic costs CPU at 8 x 8
  // that a short run on few cores feels, for figures only the emulated machine uses.
  bool mapHypercube = false;
  // A ray leaving its region beyond the scene's bounds ends there (node/scene_bounds.h) instead of crossing
  // empty regions to the screen's edge; the emulated machine keeps the paper's rays, whose costs table 2
  // was fitted to, whatever this says.
  bool endRaysLeavingScene = true;
};

// The FIFO capacity of a run: the one asked for, or the engine's own, node::scheduling::kThreadsFifoRays on
// threads and the iPSC's queues::kPaperFifoCapacity in emulated time and over MPI.
inline std::size_t fifoRaysFor(const MachineSettings& machine) {
  if (machine.queueCapacity) return *machine.queueCapacity;
  return machine.emulate || machine.mpi ? queues::kPaperFifoCapacity : node::scheduling::kThreadsFifoRays;
}

// How the regions of a run hold their objects: the structure asked for, or the engine's own: the paper's
// cells (3.3) on the emulated machine, whose costs were fitted to them (table 2) and whose light rays walk
// them (3.7.2: a cone's objects against a pyramid's); a BVH on real cores (node::chosenFor) and over MPI.
inline node::CellStructure cellsFor(const MachineSettings& machine) {
  if (machine.cells != node::CellStructure::Auto) return machine.cells;
  return machine.emulate ? node::CellStructure::Paper : node::chosenFor(machine.cells);
}

// What a report calls a cell structure.
inline const char* cellsName(node::CellStructure cells) {
  return cells == node::CellStructure::Paper ? "paper" : cells == node::CellStructure::Bvh ? "bvh" : "auto";
}

// The flow control of a run: the one asked for, or the emulated machine's own (the iPSC/1 locks, 3.5.2), or
// an overflow list on threads and MPI, so that a run there never deadlocks unless asked to lock.
inline node::FifoFull fifoFullFor(const MachineSettings& machine) {
  if (machine.fifoFull) return *machine.fifoFull;
  return machine.emulate ? machine.emulate->fifoFull : node::FifoFull::Overflow;
}

}  // namespace raycube::host
