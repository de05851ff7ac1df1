#include "host/render/render_machine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>

#include "core/intersect.h"
#include "host/engines/make_engine.h"
#include "host/prepare/box_tree.h"
#include "host/prepare/hypercube_mapping.h"
#include "host/prepare/light_volume.h"
#include "host/prepare/machine_checks.h"
#include "host/prepare/pruning.h"
#include "host/prepare/screen_partition.h"
#include "host/render/framebuffer.h"
#include "host/render/machine_progress.h"
#include "host/render/precision_dispatch.h"
#include "host/util/clock.h"
#include "host/util/parallel_for.h"
#include "host/util/progress.h"
#include "node/scheduling.h"

namespace raycube::host {
namespace {

// The iPSC was a hypercube: number the regions so that neighbours are few hops apart (3.7.1: "it is
// important to suitably map this graph on the hypercube topology"). Gray codes embed the uniform grid with
// one hop per edge; the BSP's adjacency graph gets the greedy heuristic.
struct HypercubeEmbedding {
  std::vector<std::uint32_t> nodeOfProcessor;
  Dilation dilation;
  std::size_t adjacencyEdges = 0;
  double seconds = 0;
  std::uint64_t steps = 0;  // the host's work (HostWork::mappingSteps): one per region for the Gray code
};

HypercubeEmbedding embedInHypercube(const node::RegionMap& regions, const MachineSettings& machine) {
  const Clock::time_point start = Clock::now();
  AdjacencyGraph graph;
  graph.vertices = regions.processors();
  for (int p = 0; p < regions.processors(); ++p)
    for (int n : regions.neighbours(p))
      if (n > p) graph.edges.emplace_back(p, n);
  HypercubeEmbedding out;
  out.adjacencyEdges = graph.edges.size();
  if (machine.balance == Balance::Uniform) {
    out.nodeOfProcessor = grayCodeGridMapping(machine.rows, machine.columns);
    out.steps = out.nodeOfProcessor.size();
  } else {
    out.nodeOfProcessor = mapToHypercube(graph, &out.steps);
  }
  out.dilation = dilationOf(graph, out.nodeOfProcessor);
  out.seconds = secondsSince(start);
  return out;
}

void recordEmbedding(HypercubeEmbedding embedding, MachineReport& out) {
  out.hypercubeNode = std::move(embedding.nodeOfProcessor);
  out.dilationMean = embedding.dilation.mean;
  out.dilationMax = embedding.dilation.max;
  out.hypercubeDimension = embedding.dilation.dimension;
  out.adjacencyEdges = embedding.adjacencyEdges;
  out.preprocessing.mapping = embedding.seconds;
  out.hostWork.mappingSteps = embedding.steps;
}

// The cores the processors share, for Balance::Auto: one each where every processor has a CPU of its own (the
// emulated iPSC, MPI ranks); the host's, at most one per processor, where they are its threads.
int coresSharedBy(const MachineSettings& machine) {
  const int processors = machine.rows * machine.columns;
  if (machine.emulate || machine.mpi) return processors;
  return std::clamp(int(std::thread::hardware_concurrency()), 1, processors);
}

// The host's frame buffer (3.5.1), counting what it accumulates.
class Accumulator final : public core::ContributionSink {
 public:
  explicit Accumulator(const core::View& view) : frame_(view.samplesX(), view.samplesY()) {}
  void add(const core::Contribution& c) override {
    frame_.add(c);
    ++count_;
  }
  const Framebuffer& frame() const { return frame_; }
  std::uint64_t count() const { return count_; }

 private:
  Framebuffer frame_;
  std::uint64_t count_ = 0;
};

// Phase 6: what the run measured, per processor and in total.
void reportRun(MachineRun run, const std::vector<double>& estimatedLoad, const LoadSample& load,
               std::size_t messageBytes, RenderResult& result, MachineReport& out) {
  std::vector<ProcessorReport>& processors = run.processors;
  out.messageBytes = messageBytes;
  out.estimatedLoad = estimatedLoad;
  out.subsampledRays = load.raysTraced;
  out.emulated = std::move(run.emulated);
  out.mpi = std::move(run.mpi);
  out.deadlock = std::move(run.deadlock);
  for (const ProcessorReport& pr : processors) {
    result.counters += pr.node.processed;
    out.tokenPasses += pr.node.tokenVisits;
  }
  out.tokenRounds = processors.front().node.tokenRounds;
  out.processors = std::move(processors);
  // Rays by kind: each ray counted once, where it finished (segments are in the per-processor reports).
  for (int k = 0; k < core::kRayKinds; ++k) {
    result.counters.rays[k] = 0;
    for (const auto& pr : out.processors) result.counters.rays[k] += pr.node.finished[k];
  }
}

// Phases 2 and 3 (3.2 steps 1-2, 3.7.1): sub-sample the image and project its rays (a BSP balances them,
// auto weighs them on both partitions), partition the screen, prune the database per region and light volume.
struct HostPreparation {
  LoadSample load;
  Balance balance;  // the partition made
  std::optional<PartitionForecast> forecast;
  node::MachineContext context;
  std::vector<node::NodeSetup> setups;
  AreaEstimates estimates;  // what the sub-sample puts in each region (weighed while partitioning)
  HostWork work;            // what it took, counted (the mapping's steps come later)
};

// The host's work as counted (HostWork): the sub-sampled rays as a node counts its own (each taken up,
// spawned and finished once) and the BSP's pieces, where the partition needs them: not for the grid asked
// for (the paper's first machine, 3.1) nor for one processor, which raycube samples only for its reports;
// the pruning's objects against every region, and with light volumes against every region's and the rear
// sources' volume for each light.
HostWork hostWorkOf(const LoadSample& load, const ScreenPartition& partition, const core::Scene& scene,
                    bool lightVolumes, Balance asked) {
  HostWork work;
  const std::uint64_t regions = std::uint64_t(partition.regions.processors());
  if (asked != Balance::Uniform && regions > 1) {
    work.sampling.processed = load.traced;
    work.sampling.spawned = work.sampling.finished = load.traced.rays;
    work.piecesWeighed = partition.piecesWeighed;
  }
  const std::uint64_t objects = scene.objects.size(), lights = lightVolumes ? scene.lights.size() : 0;
  work.regionTests = objects * (regions * (1 + lights) + lights);
  return work;
}

// The time since the last lap, and a new lap.
class Laps {
 public:
  double next() {
    const Clock::time_point now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  Clock::time_point last_ = Clock::now();
};

// The host's indexes for pruning, all of the sampling BVH's shape: over the objects' world boxes (light
// volumes) and eye boxes (regions); the shape itself for the processors' database BVHs.
struct SpatialQueries {
  std::shared_ptr<const core::BvhShape> shape;
  BoxTree inWorld, inEyeFrame;
};

HostPreparation prepare(const core::Scene& scene, const core::View& view, const RenderSettings& settings,
                        const MachineSettings& machine, Progress& progress, PreprocessingSeconds& seconds) {
  Laps laps;
  // The sampling's BVH of the whole scene builds on every core while this thread computes the objects'
  // boxes; its shape then serves the spatial queries and the processors' BVHs, and the tree itself their
  // light rays traced where they start.
  std::future<std::shared_ptr<const node::SceneTree>> sampled = std::async(
      std::launch::async, [&] { return std::make_shared<const node::SceneTree>(scene, settings.shading); });
  // The objects' world boxes: for where the scene lies (unless rays travel on to the screen's edge, as the
  // emulated paper's machine's do) and for the light volumes; their eye boxes for the regions.
  const bool lightVolumes = machine.lightRays != node::LightRayMode::Messages;
  const bool endRaysLeavingScene = machine.endRaysLeavingScene && !machine.emulate;
  const double sceneExtent = 2 * scene.largestCoordinate();  // bounds any ray segment in the scene
  const std::vector<core::Box> worldBoxes =
      lightVolumes || endRaysLeavingScene ? worldBoxesOf(scene) : std::vector<core::Box>{};
  std::vector<core::Box> sceneBounds;
  if (endRaysLeavingScene) sceneBounds = sceneBoundsOf(worldBoxes, sceneExtent);
  std::vector<node::EyeBox> boxes;
  boxes.reserve(scene.objects.size());
  for (const core::Object& o : scene.objects) boxes.push_back(node::eyeBoxOf(o, view, sceneExtent));
  const std::shared_ptr<const node::SceneTree> wholeScene = sampled.get();
  const core::Whitted& shading = wholeScene->shading;  // the tree's: the scene with the run's options
  // The spatial queries take the BVH's shape on the other core while this one sub-samples and partitions.
  std::future<SpatialQueries> queries = std::async(std::launch::async, [&] {
    auto shape = std::make_shared<const core::BvhShape>(wholeScene->bvh.shape());
    // The two trees side by side: built one after the other, they kept the pruning waiting.
    std::future<BoxTree> inWorld =
        std::async(std::launch::async, [&] { return BoxTree(worldBoxes, *shape); });
    BoxTree inEyeFrame(eyeFrameBoxesOf(boxes), *shape);
    return SpatialQueries{shape, inWorld.get(), std::move(inEyeFrame)};
  });
  LoadSample load = subsampleLoad(wholeScene->bvh, view, shading, machine.subsampleWindow, machine.loadMetric,
                                  lightVolumes, sceneBounds);
  seconds.sampling = laps.next();
  ScreenPartition partition = partitionScreen(view, load, machine, coresSharedBy(machine));
  HostWork work = hostWorkOf(load, partition, shading.scene(), lightVolumes, machine.balance);
  node::MachineContext context{
      view, settings.shading, std::move(partition.regions), std::move(sceneBounds), {}};
  context.fifoFull = fifoFullFor(machine);
  seconds.partitioning = laps.next();
  progress.phase("pruning");
  const SpatialQueries spatial = queries.get();
  const std::vector<core::Box> noBoxes;
  PrunedDatabase pruned = pruneDatabase(shading, view, context.regions, boxes, spatial.inEyeFrame,
                                        spatial.inWorld, endRaysLeavingScene ? worldBoxes : noBoxes, machine);
  std::vector<node::NodeSetup>& setups = pruned.setups;
  context.regionBounds = widenedForFloatHits(std::move(pruned.regionBounds), sceneExtent);
  // The processors' BVHs keep the sampling tree's shape (NodeSetup::sceneShape) and their light rays use the
  // tree, but for the emulated machine, whose costs count the box tests of trees built anew.
  if (!machine.emulate)
    for (node::NodeSetup& setup : setups) {
      setup.sceneShape = spatial.shape;
      setup.sceneTree = wholeScene;
    }
  seconds.pruning = laps.next();
  return {std::move(load),
          partition.balance,
          partition.forecast,
          std::move(context),
          std::move(setups),
          std::move(partition.estimates),
          work};
}

// When the run started, when the engine was given the processors, and when the synthesis phase started
// (preprocessing ends there: each node subdivides its region first).
struct SynthesisClock {
  Clock::time_point start;
  Clock::time_point launch;
  Clock::time_point synthesis;
};

// Phases 4 and 5: the engine runs the processors while the host accumulates every contribution, and the
// progress line follows each processor's segments against 3.7.1's sub-sampled estimate of its work.
template <class Real>
MachineRun launch(HostPreparation& host, const MachineSettings& machine,
                  const std::vector<std::uint32_t>& cubeNode, Accumulator& accumulator, Progress& progress,
                  SynthesisClock& clock, const std::function<void()>& alongsideSynthesis) {
  progress.phase("cells");  // 3.2 step 2: each processor subdivides its region, in the engine
  clock.launch = Clock::now();
  const MachineProgress work(host.estimates.expected);
  EngineHooks hooks;
  hooks.host = &accumulator;
  hooks.hostWork = &host.work;
  hooks.synthesisStarts = [&] {
    clock.synthesis = Clock::now();
    progress.phase("tracing", work.workOf({}).expected);
    alongsideSynthesis();
  };
  hooks.progress = [&](const std::vector<std::uint64_t>& evaluated) {
    const MachineProgress::Work w = work.workOf(evaluated);
    progress.setWork(std::uint64_t(w.done), w.expected);
  };
  MachineRun run = makeEngine<Real>(machine, cubeNode)->run(host.context, std::move(host.setups), hooks);
  progress.complete();
  return run;
}

template <class Real>
RenderResult renderMachineIn(const core::Scene& scene, const RenderSettings& settings,
                             const MachineSettings& asked, MachineReport* report) {
  // The engine's own FIFO capacity, flow control and cells made explicit, for the engine and the report.
  MachineSettings machine = asked;
  machine.queueCapacity = fifoRaysFor(asked);
  machine.fifoFull = fifoFullFor(asked);
  machine.cells = cellsFor(asked);
  SynthesisClock clock{Clock::now(), Clock::now(), Clock::now()};
  const core::View view(scene.camera, settings.width, settings.height, settings.sampling,
                        settings.shading.raysPerSample);
  if (machine.subsampleWindow == kAutoWindow)
    machine.subsampleWindow =
        subsampleWindowFor(view.samplesX(), view.samplesY(), machine.rows * machine.columns);
  requireMachineFits(machine, view);  // phase 1
  Progress progress("partitioning", 0, settings.progress);
  MachineReport local;
  MachineReport& out = report ? *report : local;
  out.settings = machine;
  out.balanceAsked = machine.balance;
  HostPreparation host = prepare(scene, view, settings, machine, progress, out.preprocessing);
  out.settings.balance = host.balance;
  out.partitionForecast = host.forecast;

  // Only the emulated machine's links need the embedding; otherwise it is worked out during the synthesis, if
  // the report wants it.
  std::future<HypercubeEmbedding> embedding;
  std::function<void()> alongsideSynthesis = [] {};
  out.hostWork = host.work;
  if (machine.emulate) {
    recordEmbedding(embedInHypercube(host.context.regions, out.settings), out);
    host.work.mappingSteps = out.hostWork.mappingSteps;
  } else if (machine.mapHypercube)
    alongsideSynthesis = [&] {
      embedding = std::async(std::launch::async,
                             [&] { return embedInHypercube(host.context.regions, out.settings); });
    };
  Accumulator accumulator(view);
  MachineRun run =
      launch<Real>(host, machine, out.hypercubeNode, accumulator, progress, clock, alongsideSynthesis);
  if (embedding.valid()) recordEmbedding(embedding.get(), out);

  RenderResult result;
  result.mode = "machine";
  result.precision = core::kPrecisionOf<Real>;
  result.workers = host.context.regions.processors();
  result.image = accumulator.frame().resolve(view);
  result.preprocessSeconds = std::chrono::duration<double>(clock.synthesis - clock.start).count();
  result.traceSeconds = secondsSince(clock.synthesis);
  out.preprocessing.cells = std::chrono::duration<double>(clock.synthesis - clock.launch).count();
  out.contributionsAccumulated = accumulator.count();
  reportRun(std::move(run), host.estimates.loads, host.load, sizeof(node::BasicRayMessage<Real>), result,
            out);
  if (out.deadlock) throw MachineDeadlocked(*out.deadlock);  // the report holds it, for --stats
  return result;
}

}  // namespace

RenderResult renderMachine(const core::Scene& scene, const RenderSettings& settings,
                           const MachineSettings& machine, MachineReport* report) {
  return renderInPrecision(scene, settings.precision, [&]<class Real>(const core::Scene& traced) {
    return renderMachineIn<Real>(traced, settings, machine, report);
  });
}

}  // namespace raycube::host
