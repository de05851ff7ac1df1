#include "host/machine.h"

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
#include "host/box_tree.h"
#include "host/framebuffer.h"
#include "host/hypercube_mapping.h"
#include "host/light_volume.h"
#include "host/machine_checks.h"
#include "host/machine_engine.h"
#include "host/machine_progress.h"
#include "host/parallel_for.h"
#include "host/precision_dispatch.h"
#include "host/progress.h"
#include "host/screen_partition.h"
#include "node/scheduling.h"

namespace raycube::host {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Bounds of x over {x in [lo, hi], a z <= x <= b z, z in [z0, z1]} (a, b may be infinite).
std::pair<double, double> clipToWedge(double lo, double hi, double a, double b, double z0, double z1) {
  if (std::isfinite(a)) lo = std::max(lo, std::min(a * z0, a * z1));
  if (std::isfinite(b)) hi = std::min(hi, std::max(b * z0, b * z1));
  return {lo, hi};
}

// Where the region's light rays can start: the part in front of the eye of each of its objects' boxes,
// clipped to the region's wedge, all in one eye-frame box (3.7.2 uses the region's vertices).
node::LightSources withCorners(node::LightSources sources, const core::View& view) {
  if (sources.eyeBox.empty()) return sources;
  sources.eyeBox = sources.eyeBox.padded(core::kCellMarginRelative);
  for (int corner = 0; corner < 8; ++corner) {
    const core::Box& e = sources.eyeBox;
    const core::Vec3 eyeFrame(corner & 1 ? e.hi.x : e.lo.x, corner & 2 ? e.hi.y : e.lo.y,
                              corner & 4 ? e.hi.z : e.lo.z);
    sources.corners.push_back(node::worldFromEyeFrame(view, eyeFrame));
  }
  return sources;
}

node::LightSources lightSourcesOf(const node::ColumnSlab& region, const std::vector<std::uint32_t>& objects,
                                  const std::vector<node::EyeBox>& boxes, const core::View& view) {
  node::LightSources sources;
  for (std::uint32_t o : objects) {
    const node::EyeBox& b = boxes[o];
    const double z0 = std::max(b.lo.z, 0.0), z1 = b.hi.z;
    if (z0 > z1) continue;
    const auto [x0, x1] = clipToWedge(b.lo.x, b.hi.x, region.sLo, region.sHi, z0, z1);
    const auto [y0, y1] = clipToWedge(b.lo.y, b.hi.y, region.qLo, region.qHi, z0, z1);
    if (x0 > x1 || y0 > y1) continue;
    sources.eyeBox.extend(core::Vec3(x0, y0, z0));
    sources.eyeBox.extend(core::Vec3(x1, y1, z1));
  }
  return withCorners(sources, view);
}

// Light rays can also start on the rear parts of objects reaching behind the eye (any processor's).
node::LightSources rearLightSourcesOf(const std::vector<std::uint32_t>& rear,
                                      const std::vector<node::EyeBox>& boxes, const core::View& view) {
  node::LightSources sources;
  for (std::uint32_t o : rear) {
    sources.eyeBox.extend(boxes[o].lo);
    sources.eyeBox.extend(core::Vec3(boxes[o].hi.x, boxes[o].hi.y, std::min(boxes[o].hi.z, 0.0)));
  }
  return withCorners(sources, view);
}

// The lists a processor's cells index, rewritten into its database's local indices.
std::vector<std::vector<std::uint32_t>*> cellListsOf(node::NodeSetup& setup) {
  return {&setup.objects, &setup.rearObjects};
}

// What the light volumes add to a processor (3.7.2), for its report: their objects summed over the lights,
// and how many of those its region's own objects do not already include (all lists ascending).
void countLightObjects(const std::vector<std::vector<std::uint32_t>>& lightObjects, node::NodeSetup& setup) {
  for (const std::vector<std::uint32_t>& objects : lightObjects) {
    setup.lightObjects += objects.size();
    std::size_t inRegion = 0;  // both ascending: one walk along the two
    for (auto r = setup.objects.cbegin(), l = objects.cbegin();
         r != setup.objects.cend() && l != objects.cend();) {
      if (*r < *l) {
        ++r;
      } else if (*l < *r) {
        ++l;
      } else {
        ++inRegion, ++r, ++l;
      }
    }
    setup.extraLightObjects += objects.size() - inRegion;
  }
}

// A processor needing most of the scene holds all of it, the database and tree every such processor shares:
// an object held without being needed costs its BVH box tests, never a hit (it lies outside the region and
// off every light ray starting there), and one database replaces many nearly equal ones (gears 4 at 8x8: 64
// processors need 7,396 to 9,345 of its 9,345 objects). Not when emulating, whose costs count the box tests.
bool holdsWholeScene(const std::vector<std::uint32_t>& held, const core::Scene& scene,
                     const MachineSettings& machine) {
  return !machine.emulate && 2 * held.size() > scene.objects.size();
}

// Whether the processors run in the host's address space and read its scene in place (RegionDatabase): not
// on MPI ranks, nor when emulating, whose nodes hold copies as the iPSC's did.
bool readsSceneInPlace(const MachineSettings& machine) {
  return !machine.emulate && !machine.mpi;
}

// Each processor's database of the objects its lists name, the lists rewritten into its indices; the
// processors holding the same objects share one database (the ground polygon's light volumes can make that
// all of them).
void giveDatabases(std::vector<node::NodeSetup>& setups, const std::vector<std::vector<std::uint32_t>>& held,
                   const core::Scene& scene, const std::vector<node::EyeBox>& boxes, bool inPlace) {
  // The distinct sets in the order processors first name them, each copied once, on all cores.
  auto bySet = [](const std::vector<std::uint32_t>* a, const std::vector<std::uint32_t>* b) { return *a < *b; };
  std::map<const std::vector<std::uint32_t>*, std::size_t, decltype(bySet)> distinct(bySet);
  std::vector<std::size_t> setOf(setups.size());
  std::vector<const std::vector<std::uint32_t>*> sets;
  for (std::size_t p = 0; p < setups.size(); ++p) {
    const auto [at, added] = distinct.try_emplace(&held[p], sets.size());
    if (added) sets.push_back(&held[p]);
    setOf[p] = at->second;
  }
  std::vector<std::shared_ptr<const node::RegionDatabase>> databases(sets.size());
  const core::SceneFeatures features = inPlace ? scene.features() : core::SceneFeatures{};
  parallelFor(int(sets.size()), [&](int d) {
    const std::vector<std::uint32_t>& objects = *sets[std::size_t(d)];
    databases[std::size_t(d)] = std::make_shared<const node::RegionDatabase>(
        inPlace ? node::regionDatabaseIn(scene, features, objects) : node::regionDatabaseOf(scene, objects));
  });
  for (std::size_t p = 0; p < setups.size(); ++p) setups[p].database = databases[setOf[p]];
  parallelFor(int(setups.size()), [&](int p) {
    node::NodeSetup& setup = setups[std::size_t(p)];
    setup.objectBoxes = node::eyeBoxesOf(boxes, setup.objects);
    node::toLocalIndices(*setup.database, cellListsOf(setup));
  });
}

std::vector<core::Box> eyeFrameBoxesOf(const std::vector<node::EyeBox>& boxes) {
  std::vector<core::Box> out;
  out.reserve(boxes.size());
  for (const node::EyeBox& b : boxes) out.push_back(core::Box{b.lo, b.hi});
  return out;
}

std::vector<core::Box> worldBoxesOf(const core::Scene& scene) {
  std::vector<core::Box> out;
  out.reserve(scene.objects.size());
  for (const core::Object& o : scene.objects) out.push_back(core::boundsOf(o, core::kCellMarginRelative));
  return out;
}

// Boxes holding objects' world boxes (padded as the cells pad them), widened for a float ray's hit error
// over the scene's longest segment, as the eye boxes are.
std::vector<core::Box> widenedForFloatHits(std::vector<core::Box> bounds, double sceneExtent) {
  const double floatHitError = core::kFloatHitErrorRelative * sceneExtent;
  for (core::Box& b : bounds)
    if (!b.empty()) b = core::Box{b.lo - floatHitError, b.hi + floatHitError};
  return bounds;
}

// Where the scene lies: a few boxes holding every object's world box.
std::vector<core::Box> sceneBoundsOf(const std::vector<core::Box>& worldBoxes, double sceneExtent) {
  return widenedForFloatHits(medianCover(worldBoxes, node::scheduling::kSceneBoundsBoxes), sceneExtent);
}

// Where each region's objects lie (MachineContext::regionBounds): the box of the world boxes of the objects
// touching it (its cells' objects; the rear ones lie behind the eye).
core::Box regionBoundsOf(const std::vector<std::uint32_t>& objects,
                         const std::vector<core::Box>& worldBoxes) {
  core::Box bounds;
  for (std::uint32_t o : objects) bounds.extend(worldBoxes[o]);
  return bounds;
}

// The processors' setups, and where each region's objects lie where the world boxes are given.
struct PrunedDatabase {
  std::vector<node::NodeSetup> setups;
  std::vector<core::Box> regionBounds;
};

// 3.2 step 1: each processor receives the objects that touch its region; objects reaching behind the eye
// plane go to every processor (see EyeFrameRay: the rear space belongs to all). 3.7.2: with light cones or
// pyramids, also the objects its light rays can meet.
PrunedDatabase pruneDatabase(const core::Whitted& shading, const core::View& view,
                             const node::RegionMap& regions, const std::vector<node::EyeBox>& boxes,
                             const BoxTree& inEyeFrame, const BoxTree& inWorld,
                             const std::vector<core::Box>& worldBoxesForBounds,
                             const MachineSettings& machine) {
  const core::Scene& scene = shading.scene();
  std::vector<std::uint32_t> rear;
  for (std::uint32_t o = 0; o < boxes.size(); ++o)
    if (node::reachesBehindEye(boxes[o])) rear.push_back(o);
  // Spatial queries: the objects' eye boxes for the regions, their world boxes for the light volumes.
  const bool lightVolumes = machine.lightRays != node::LightRayMode::Messages;
  std::vector<std::vector<std::uint32_t>> rearLightObjects;
  node::LightSources rearSources;
  // Eye rays meet objects only in front of the eye: without reflected or refracted rays, no light ray starts
  // behind it.
  if (lightVolumes && shading.spawnsSecondaryRays()) {
    rearSources = rearLightSourcesOf(rear, boxes, view);
    for (const core::Light& light : scene.lights)
      rearLightObjects.push_back(
          objectsInLightVolume(machine.lightRays, light.position, rearSources, inWorld));
  }
  std::vector<node::NodeSetup> setups(std::size_t(regions.processors()));
  std::vector<core::Box> regionBounds(worldBoxesForBounds.empty() ? 0 : setups.size());
  std::vector<std::vector<std::uint32_t>> heldBy(setups.size());
  const std::vector<std::uint32_t> everyObject = core::everyObjectOf(scene);
  parallelFor(regions.processors(), [&](int p) {
    const node::ScreenRect r = regions.screenRectOf(p);
    const node::ColumnSlab region{r.s0, r.s1, r.q0, r.q1, 0, core::kInfinity};
    node::NodeSetup setup;
    setup.id = p;
    setup.cells = machine.emulate && machine.cells == node::CellStructure::Auto ? node::CellStructure::Paper
                                                                               : machine.cells;
    setup.cellLevel = machine.cellLevel;
    setup.rearObjects = rear;
    setup.objects =
        inEyeFrame.query([&](const core::Box& b) { return node::mayTouch(node::EyeBox{b.lo, b.hi}, region); });
    if (!regionBounds.empty())
      regionBounds[std::size_t(p)] = regionBoundsOf(setup.objects, worldBoxesForBounds);
    setup.lightRays = machine.lightRays;
    // The light volumes' objects only decide what the processor holds: its database's BVH finds them.
    std::vector<std::vector<std::uint32_t>*> held{&setup.objects, &setup.rearObjects};
    std::vector<std::vector<std::uint32_t>> lightObjects;
    if (lightVolumes) {
      setup.lightSources = lightSourcesOf(region, setup.objects, boxes, view);
      for (const core::Light& light : scene.lights)
        lightObjects.push_back(objectsInLightVolume(machine.lightRays, light.position, setup.lightSources, inWorld));
      setup.rearLightSources = rearSources;
      countLightObjects(lightObjects, setup);
      for (auto* lists : {&lightObjects, &rearLightObjects})
        for (std::vector<std::uint32_t>& objects : *lists) held.push_back(&objects);
    }
    heldBy[std::size_t(p)] = node::heldObjectsOf(held, scene.objects.size());
    if (holdsWholeScene(heldBy[std::size_t(p)], scene, machine)) heldBy[std::size_t(p)] = everyObject;
    setups[std::size_t(p)] = std::move(setup);
  });
  giveDatabases(setups, heldBy, scene, boxes, readsSceneInPlace(machine));
  return {std::move(setups), std::move(regionBounds)};
}

// The iPSC was a hypercube: number the regions so that neighbours are few hops apart (3.7.1: "it is
// important to suitably map this graph on the hypercube topology"). Gray codes embed the uniform grid with
// one hop per edge; the BSP's adjacency graph gets the greedy heuristic.
struct HypercubeEmbedding {
  std::vector<std::uint32_t> nodeOfProcessor;
  Dilation dilation;
  std::size_t adjacencyEdges = 0;
  double seconds = 0;
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
  out.nodeOfProcessor = machine.balance == Balance::Uniform ? grayCodeGridMapping(machine.rows, machine.columns)
                                                            : mapToHypercube(graph);
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
  out.simulated = std::move(run.simulated);
  out.distributed = std::move(run.distributed);
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
};

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
    // The two trees side by side: sombrero 3's pruning waited 13-25 ms for them, built one after the other.
    std::future<BoxTree> inWorld =
        std::async(std::launch::async, [&] { return BoxTree(worldBoxes, *shape); });
    BoxTree inEyeFrame(eyeFrameBoxesOf(boxes), *shape);
    return SpatialQueries{shape, inWorld.get(), std::move(inEyeFrame)};
  });
  LoadSample load = subsampleLoad(wholeScene->bvh, view, shading, machine.subsampleWindow, machine.loadMetric,
                                  lightVolumes, sceneBounds);
  seconds.sampling = laps.next();
  ScreenPartition partition = partitionScreen(view, load, machine, coresSharedBy(machine));
  node::MachineContext context{
      view, settings.shading, std::move(partition.regions), std::move(sceneBounds), {}};
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
  return {std::move(load),    partition.balance, partition.forecast,
          std::move(context), std::move(setups), std::move(partition.estimates)};
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
  // The engine's own FIFO capacity made explicit, for the engine and the report.
  MachineSettings machine = asked;
  machine.queueCapacity = fifoRaysFor(asked);
  SynthesisClock clock{Clock::now(), Clock::now(), Clock::now()};
  const core::View view(scene.camera, settings.width, settings.height, settings.sampling,
                        settings.shading.raysPerSample);
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
  if (machine.emulate)
    recordEmbedding(embedInHypercube(host.context.regions, out.settings), out);
  else if (machine.mapHypercube)
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
