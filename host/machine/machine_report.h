#pragma once
// What the message-passing machine measured (Priol & Bouatouch 3.6, 3.7): per processor its counts, FIFOs
// and time; the preprocessing's phases; and what an engine with a clock of its own (SimGrid) or with
// processes of its own (MPI) adds.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "host/machine/deadlock.h"
#include "host/machine/host_work.h"
#include "host/machine/machine_settings.h"
#include "node/logical_processor.h"
#include "queues/queue_stats.h"

namespace raycube::host {

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
// Blocked: waiting with rays for a full neighbour (locked, under --fifo-full lock). Forwarding: its node's
// communication task relaying others' messages (store and forward), on the same CPU.
enum class ProcessorState : std::uint8_t { Computing, Blocked, Idle, Forwarding };
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
// The host's preparation in simulated time (3.2 steps 1-2, 3.7.1): its counted work (HostWork) at the
// manager's speed, phase after phase, then each node's setup sent over the manager's links, one node after
// the other; it ends when the last node has its setup. Table 2 leaves it out ("a few minutes").
struct HostPreprocessing {
  double sampling = 0, partitioning = 0, pruning = 0, mapping = 0, transfer = 0;  // simulated seconds
  double seconds = 0;                     // all of it: the synthesis starts then
  std::uint64_t messages = 0, bytes = 0;  // the setups sent
};
struct EmulatedRun {
  std::string platform;
  double makespan = 0;              // simulated seconds from the start of synthesis to the last contribution
  HostPreprocessing preprocessing;  // before the synthesis
  double endToEnd() const { return preprocessing.seconds + makespan; }
  double nodeSpeed = 0;           // node-0's speed, flop-equivalents per second (what --fit scales)
  std::uint64_t rayMessages = 0;  // simulated ray messages, relays included
  double wallSeconds = 0;         // what the simulation took on this host
  std::vector<LinkTraffic> links;
  std::vector<StateInterval> timeline;
};

// A run over MPI (the MPI engine): what each rank held and what crossed between ranks.
struct RankReport {
  int rank = 0;
  int processors = 0;              // logical processors it ran (the host, rank 0, runs none)
  std::uint64_t objects = 0;       // objects its processors held, each its own copy (RegionDatabase)
  std::uint64_t jobBytes = 0;      // the setups and context it received (rank 0: sent to all)
  std::uint64_t peakRssBytes = 0;  // its process's peak resident memory (getrusage)
  std::uint64_t messagesSent = 0, bytesSent = 0, messagesReceived = 0, bytesReceived = 0;  // MPI
  std::uint64_t rayMessages = 0, raysSent = 0;  // MPI messages carrying rays, and the rays in them
};
struct MpiRun {
  std::size_t rayBatch = 0;
  std::vector<RankReport> ranks;  // rank 0 first
};

// Where the preprocessing time goes (3.2 steps 1-2, 3.7.1), in seconds.
struct PreprocessingSeconds {
  double sampling = 0;  // the sub-sampled rays (3.7.1), and alongside them the spatial queries pruning uses
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
  HostWork hostWork;  // the host's work before the synthesis, counted
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
  std::optional<EmulatedRun> emulated;
  std::optional<MpiRun> mpi;
  std::uint64_t tokenPasses = 0;     // token visits over all processors
  std::optional<Deadlock> deadlock;  // --fifo-full lock: the run stopped there; the counts are up to it
};

}  // namespace raycube::host
