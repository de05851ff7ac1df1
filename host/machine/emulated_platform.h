#pragma once
// A machine to emulate in simulated time (the SimGrid engine): how fast its nodes compute, what its links
// cost, how messages are routed, and what each operation the node counts costs. Time is charged from
// counted work, never measured, so a simulated time is the same on every run and every computer.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "host/machine/host_work.h"
#include "node/logical_processor.h"
#include "queues/routing.h"

namespace raycube::host {

// What each operation a node counts costs. Computation in flop-equivalents (hand counts of the floating-point
// operations in core/ and node/): only their ratios matter, the platform's node speed turns them into
// seconds; or, with a cost file's `unit seconds` line (what `raycube calibrate` writes), in seconds of a node
// of the platform, measured. Messages in seconds of the CPU that pays them (the iPSC's were software
// overheads measured on the machine, not flops): the sender's, the receiver's, and a relaying node's under
// store and forward.
struct CostTable {
  double sphereTest = 25;     // oc = o - c, b = oc.d, c = oc.oc - r^2, b^2 - c, sqrt, two roots
  double coneTest = 60;       // a quadric in the cone's frame plus two caps
  double polygonTest = 20;    // plane hit: n.d, (dist - n.o) / n.d, the point
  double polygonVertex = 6;   // the crossing test, per edge
  double patchTest = 45;      // a triangle and the interpolated normal
  double cellStep = 6;        // one step of the walk through the region's cells (3.3), or one BVH node tested
  double raySegment = 50;     // a ray taken up in a region: eye-frame conversion, entry cell
  double rayFinished = 60;    // shading where a ray ends: point, normal, Phong terms, or the light term
  double raySpawned = 25;     // a reflected, refracted or light ray: direction, weight, owner lookup
  double contribution = 5;    // a piece of pixel colour into the block for the host
  double sendSeconds = 0;     // a message sent (a ray, or the token), on the sender's CPU
  double receiveSeconds = 0;  // a message received, on the receiver's CPU
  double relaySeconds = 0;    // store and forward: a node receives and re-sends another's message
  double accumulateSeconds = 0;  // the host: a contribution received and added to the frame buffer (3.4)
  // The host's own work before the synthesis (HostWork), at the manager's speed. Its sub-sampled rays cost
  // what a node's rays cost (the fields above); these price the rest, hand counts as above.
  double segmentClip = 20;  // a sub-sampled segment piece weighed at a BSP line or clipped (Liang-Barsky)
  double regionTest = 25;   // an object's eye box against a region's wedge (node::mayTouch: 8 divisions,
                            // margins, min/max, compares) or against a light volume
  double mappingStep = 2;   // the embedding: one node's hops to a vertex's neighbours weighed (popcount, add)

  // What a node's counted work costs: its computation in flop-equivalents (or seconds, ComputeUnit), its
  // messages in seconds (each linear: a difference of two calls is the cost of the work between them). A
  // token visit is a message received and one sent (3.6).
  double flopsOf(const node::NodeStats& stats) const;
  double messageSecondsOf(const node::NodeStats& stats) const;
  // What the host's work costs, phase by phase, in flop-equivalents.
  double samplingFlopsOf(const HostWork& work) const { return flopsOf(work.sampling); }
  double partitioningFlopsOf(const HostWork& work) const { return segmentClip * double(work.piecesWeighed); }
  double pruningFlopsOf(const HostWork& work) const { return regionTest * double(work.regionTests); }
  double mappingFlopsOf(const HostWork& work) const { return mappingStep * double(work.mappingSteps); }
  bool operator==(const CostTable&) const = default;
};

using queues::Routing;

// What a cost table's computation costs are in: flop-equivalents (scaled by the node speed) or seconds.
enum class ComputeUnit : std::uint8_t { FlopEquivalents, Seconds };

// A machine is data: a SimGrid platform (hosts node-0 ... node-<2^d - 1> and manager, links, routes) and a
// cost table. The built-in ones ship as host/machine/platforms/<name>.xml and <name>.costs.
struct EmulatedPlatform {
  std::string name;
  std::filesystem::path platformFile;  // the SimGrid platform
  Routing routing = Routing::StoreAndForward;
  // What a send into a full FIFO does on this machine unless --fifo-full says otherwise: the iPSC/1's
  // synthesis task locked (3.5.2), a modern cluster's may overflow into memory.
  node::FifoFull fifoFull = node::FifoFull::Overflow;
  std::optional<double> nodeSpeed;  // a cost table's nodeSpeed (flop-equivalents/s): replaces the platform's
  ComputeUnit computeUnit = ComputeUnit::FlopEquivalents;  // a cost table's `unit`
  // --ranks N: the run is an N-rank MPI job on one computer, node-0 (mpirun without a host file): every
  // processor and the host run on node-0 and share its cores (SimGrid's `core` count), as Open MPI's ranks
  // share the machine's. 0: each processor on a host of its own (node-<hypercube node>).
  int ranks = 0;
  CostTable costs;
};

// Where the shipped platforms are, in the order looked at: $RAYCUBE_PLATFORMS if set; platforms/ beside the
// program (the build tree); <prefix>/share/raycube/platforms for a program installed in <prefix>/bin; the
// build tree's copy (for test programs).
std::vector<std::filesystem::path> platformDirectories();
// "ipsc1" or "cluster" (<name>.xml and <name>.costs in the first of platformDirectories() that has them);
// throws std::invalid_argument naming the choices for another name, std::runtime_error naming the places
// looked at when the files are missing.
EmulatedPlatform builtinPlatform(std::string_view name);
// --platform FILE.xml [--costs FILE]: a SimGrid platform and a cost table of "name value" lines (any
// CostTable field, plus nodeSpeed, routing store-and-forward|direct and fifoFull lock|overflow). Errors name
// file:line. The built-in platforms come this way too.
// CostTable field, plus nodeSpeed, unit flop-equivalents|seconds and routing store-and-forward|direct).
// Errors name file:line. The built-in platforms come this way too.
EmulatedPlatform userPlatform(const std::filesystem::path& platformFile, const std::filesystem::path& costs);
void applyCostFile(const std::filesystem::path& costs, EmulatedPlatform& platform);

}  // namespace raycube::host
