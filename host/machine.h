#pragma once
// The message-passing machine (Priol & Bouatouch section 3): the host partitions the screen into pixel
// areas (an R x C grid, 3.1, or a BSP of equal estimated loads, 3.7.1), prunes the database for each region
// (3.2 step 1) and for its light volumes (3.7.2), starts one thread per logical processor, accumulates the
// contributions they send (3.4, 3.5.1) and stops when the token ring has proved termination (3.6).
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "host/emulated_platform.h"
#include "host/load_estimate.h"
#include "host/render_result.h"
#include "host/render_settings.h"
#include "node/logical_processor.h"
#include "node/scheduling.h"
#include "queues/queue_stats.h"
#include "queues/spsc_queue.h"

namespace raycube::host {

enum class Balance : std::uint8_t {
  Auto,     // whichever of the two the sub-sampled estimate says finishes first (host/screen_partition.h)
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

struct MachineSettings {
  int rows = 4;
  int columns = 4;
  Balance balance = Balance::Auto;  // with Bsp only rows x columns (the processor count) matters
  int subsampleWindow = 8;         // 3.7.1: one sub-sampled pixel per w x w window
  LoadMetric loadMetric = LoadMetric::Cost;
  // Rays per face FIFO (3.5.2); none: the engine's own (fifoRaysFor).
  std::optional<std::size_t> queueCapacity;
  // How each region holds its objects. Auto: a BVH in every region (node::chosenFor), but the paper's
  // cells whenever the machine is emulated, whose costs were fitted to them (table 2).
  node::CellStructure cells = node::CellStructure::Auto;
  int cellLevel = 2;                // recursive halvings of each pixel area into super-cells (3.3)
  node::LightRayMode lightRays = node::LightRayMode::Pyramid;  // 3.7.2
  unsigned jitterSeed = 0;  // tests: > 0 injects random delays around every transport operation
  // Threads: rays waiting for room machine-wide from which no primary ray is shot (node::scheduling::
  // kMachineBacklogLimit); tests lower it to hold primaries back often.
  std::size_t backlogLimit = node::scheduling::kMachineBacklogLimit;
  std::optional<EmulatedPlatform> emulate;  // set: run on SimGrid in that machine's simulated time
  bool mpi = false;         // run the processors on the other ranks of MPI_COMM_WORLD (host/mpi_machine.h)
  std::size_t rayBatch = 16;  // MPI: rays per message to one rank, at most
  // Embed the regions in the hypercube (3.7.1) for the report, during the synthesis, when not emulating; the
  // emulated machine always does, its links need it. Off by default: the BSP's heuristic costs up to 0.1 s
  // of CPU at 8 x 8, which a short run on few cores feels, for figures only the emulated machine uses.
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

struct ProcessorReport {
  node::NodeStats node;
  std::array<queues::QueueStats, node::kFaces> outgoing;  // FIFOs it sends into
  // Kept by the engine's driver, in its clock (wall seconds for threads, simulated seconds on SimGrid):
  double blockedSeconds = 0;  // waiting while holding rays its full neighbours would not take (3.6)
  double idleSeconds = 0;     // waiting with nothing to do
  double computeSeconds = 0;  // simulated only: charged for its own counted work
  double forwardSeconds = 0;  // simulated only: relaying others' messages (store and forward)
};

// A run in simulated time (the SimGrid engine): the emulated machine's clock.
enum class ProcessorState : std::uint8_t { Computing, Blocked, Idle };
struct StateInterval {
  double start = 0, end = 0;  // simulated seconds
  std::uint32_t processor = 0;
  ProcessorState state = ProcessorState::Computing;
};
struct LinkTraffic {
  std::uint32_t from = 0, to = 0;  // hypercube nodes; to == kHostNode: the link to the host
  std::uint64_t messages = 0, bytes = 0;
};
inline constexpr std::uint32_t kHostNode = UINT32_MAX;
struct SimulatedRun {
  std::string platform;
  double makespan = 0;  // simulated seconds from the start of synthesis to the last contribution
  std::uint64_t rayMessages = 0;  // simulated ray messages, relays included
  double wallSeconds = 0;         // what the simulation took on this host
  std::vector<LinkTraffic> links;
  std::vector<StateInterval> timeline;
};

// A run over MPI (the MPI engine): what each rank held and what crossed between ranks.
struct RankReport {
  int rank = 0;
  int processors = 0;            // logical processors it ran (the host, rank 0, runs none)
  std::uint64_t objects = 0;     // objects its processors held, each its own copy (RegionDatabase)
  std::uint64_t jobBytes = 0;    // the setups and context it received (rank 0: sent to all)
  std::uint64_t peakRssBytes = 0;  // its process's peak resident memory (getrusage)
  std::uint64_t messagesSent = 0, bytesSent = 0, messagesReceived = 0, bytesReceived = 0;  // MPI
  std::uint64_t rayMessages = 0, raysSent = 0;  // MPI messages carrying rays, and the rays in them
};
struct DistributedRun {
  std::size_t rayBatch = 0;
  std::vector<RankReport> ranks;  // rank 0 first
};

// Where the preprocessing time goes (3.2 steps 1-2, 3.7.1), in seconds.
struct PreprocessingSeconds {
  double sampling = 0;      // the sub-sampled rays (3.7.1), and alongside them the spatial queries pruning uses
  double partitioning = 0;  // the grid, or the BSP of the sub-sampled load
  double pruning = 0;       // each region's database and light volumes (3.2 step 1, 3.7.2)
  double cells = 0;         // the processors building their structures, in the engine (3.2 step 2)
  // Embedding the regions in the hypercube (3.7.1): before the run when emulating the machine, whose links
  // need it; otherwise during the synthesis, on a thread of its own, and not part of the preprocessing.
  double mapping = 0;
};

struct MachineReport {
  MachineSettings settings;  // as run: its balance the partition made (Uniform or Bsp)
  Balance balanceAsked = Balance::Auto;
  std::optional<PartitionForecast> partitionForecast;  // Auto's, where both partitions fitted
  PreprocessingSeconds preprocessing;
  // Figure 15: per processor, the load estimated from the sub-sampled rays (scaled to the image), in the
  // metric used to partition; and how many rays were sub-sampled.
  std::vector<double> estimatedLoad;
  std::uint64_t subsampledRays = 0;
  // The regions on the iPSC's hypercube: node number per processor, and hops per adjacency edge. Empty when
  // not mapped (settings.mapHypercube false and not emulating).
  std::vector<std::uint32_t> hypercubeNode;
  double dilationMean = 0;
  int dilationMax = 0;
  int hypercubeDimension = 0;
  std::size_t adjacencyEdges = 0;
  std::vector<ProcessorReport> processors;
  std::size_t messageBytes = 0;  // sizeof the ray message in the render's precision
  std::uint64_t contributionsAccumulated = 0;
  std::uint32_t tokenRounds = 0;  // started by processor 0
  std::optional<SimulatedRun> simulated;
  std::optional<DistributedRun> distributed;
  std::uint64_t tokenPasses = 0;  // token visits over all processors
};

RenderResult renderMachine(const core::Scene& scene, const RenderSettings& settings,
                           const MachineSettings& machine, MachineReport* report = nullptr);

}  // namespace raycube::host
