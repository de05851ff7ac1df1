#include "node/logical_processor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/ray_tree.h"
#include "core/transmission.h"
#include "node/regions_ahead.h"
#include "node/scene_bounds.h"
#include "node/scheduling.h"

namespace raycube::node {
namespace {

// A walk's passes in evaluate(): the front part, the rear part, and one more for an eye ray whose origin
// rounding put just behind the eye plane (it is in front of the eye wherever its pixel's pyramid is).
constexpr int kPartsOfALine = 3;

// Test memos for every object the walk can meet, the region's, the rear's and its light volumes': indices
// up to the largest.
std::size_t memosFor(const NodeSetup& setup) {
  std::uint32_t end = 0;
  for (const std::vector<std::uint32_t>* list : {&setup.objects, &setup.rearObjects})
    for (std::uint32_t o : *list) end = std::max(end, o + 1);
  for (const LightSources* sources : {&setup.lightSources, &setup.rearLightSources})
    for (const std::vector<std::uint32_t>& list : sources->volumeObjects)
      for (std::uint32_t o : list) end = std::max(end, o + 1);
  return end;
}

// With the paper's cells, the host gives every light's volume for the sources light rays can start from.
void requireLightVolumes(const NodeSetup& setup, std::size_t lights) {
  for (const LightSources* sources : {&setup.lightSources, &setup.rearLightSources}) {
    if (sources->eyeBox.empty()) continue;
    bool given = sources->volumeObjects.size() == lights && sources->volumeBoxes.size() == lights;
    for (std::size_t l = 0; given && l < lights; ++l)
      given = sources->volumeBoxes[l].size() == sources->volumeObjects[l].size();
    if (!given)
      throw std::invalid_argument(
          "processor " + std::to_string(setup.id) +
          ": the paper's cells need each light's volume, its objects with their eye boxes");
  }
}

// A light volume's objects reaching the eye plane or behind it: what the rear part of its rays can meet.
std::vector<std::vector<std::uint32_t>> rearPartsOf(const LightSources& sources) {
  std::vector<std::vector<std::uint32_t>> rear(sources.volumeObjects.size());
  for (std::size_t l = 0; l < rear.size(); ++l)
    for (std::size_t k = 0; k < sources.volumeObjects[l].size(); ++k)
      if (reachesBehindEye(sources.volumeBoxes[l][k])) rear[l].push_back(sources.volumeObjects[l][k]);
  return rear;
}

// A ray setting out from where it starts, for processor `destination`, carrying nothing yet. Built where it
// is used (see LogicalProcessor::local_).
template <class Real>
BasicRayMessage<Real> departing(const core::BasicTracedRay<Real>& ray, int destination) {
  return {.ray = ray, .tEnter = ray.ray.tMin, .destination = std::uint16_t(destination)};
}

// Per neighbour, in neighbours() order: the face of region `id` it lies across.
std::vector<Face> facesTowardNeighbours(const RegionMap& regions, int id) {
  std::vector<Face> faces;
  for (int n : regions.neighbours(id)) faces.push_back(regions.faceToward(id, n));
  return faces;
}

}  // namespace

template <class Real>
LogicalProcessor<Real>::LogicalProcessor(const MachineContext& context, NodeSetup setup,
                                         BasicTransport<Real>& transport)
    : context_(context),
      setup_(std::move(setup)),
      scene_(setup_.database->traced()),
      shading_(scene_, context.shading, setup_.database->features()),
      transport_(transport),
      area_(context.regions.areaOf(setup_.id)),
      structure_(chosenFor(setup_.cells)),
      cells_(area_, context.lines(), structure_ == CellStructure::Bvh ? 0 : setup_.cellLevel,
             structure_ == CellStructure::Paper, setup_.objects, setup_.objectBoxes),
      neighbours_(context.regions.neighbours(setup_.id)),
      overflow_(neighbours_.size()),
      faceOf_(facesTowardNeighbours(context.regions, setup_.id)),
      inbox_(scheduling::kInboxBatch),
      locks_(context.fifoFull == FifoFull::Lock),
      memoStamp_(structure_ == CellStructure::Paper ? memosFor(setup_) : 0, 0),
      memoT_(memoStamp_.size(), 0.0),
      carriesAhead_(structure_ == CellStructure::Bvh && setup_.database->inPlace != nullptr),
      termination_(setup_.id) {
  setup_.objectBoxes = {};  // the cells are cut
  stats_.id = setup_.id;
  stats_.area = area_;
  stats_.objects = cells_.objectCount();
  stats_.rearObjects = setup_.rearObjects.size();
  stats_.heldObjects = setup_.database->size();
  stats_.cells = cells_.cellCount();
  stats_.bvh = structure_ == CellStructure::Bvh;
  // The whole scene's shape restricted to the region's objects where the host shares it (as the database's
  // tree), with leaves of one object as a build makes them: a fraction of a build's time for a few percent
  // more box tests, about even with building anew over a whole run. Leaves of two cost more tests.
  if (stats_.bvh)
    regionBvh_ = std::make_unique<const core::BasicBvh<Real>>(core::bvhOver<Real>(
        scene_, shading_, setup_.objects, setup_.sceneShape.get(), setup_.database->wholeIdOf()));
  if (setup_.lightRays != LightRayMode::Messages && walksLightCells()) {
    requireLightVolumes(setup_, scene_.lights.size());
    const LightSources* sources[2] = {&setup_.lightSources, &setup_.rearLightSources};
    for (int s = 0; s < 2; ++s) {
      for (std::size_t l = 0; l < sources[s]->volumeObjects.size(); ++l) {
        const std::vector<EyeBox>& boxes = sources[s]->volumeBoxes[l];
        lightCells_[s].emplace_back(area_, context.lines(), setup_.cellLevel, true,
                                    sources[s]->volumeObjects[l], boxes, true);
      }
      lightRearObjects_[s] = rearPartsOf(*sources[s]);
    }
  } else if (setup_.lightRays != LightRayMode::Messages) {
    lightRayTree_.emplace(setup_.database, context.shading, setup_.sceneShape.get(), setup_.sceneTree);
  }
  stats_.lightObjects = setup_.lightObjects;
  stats_.extraLightObjects = setup_.extraLightObjects;
}

// 3.5.2: received rays first, then more primary rays; the token moves only in the second phase.
template <class Real>
Step LogicalProcessor<Real>::step(int primaries) {
  stepping_.store(true, std::memory_order_relaxed);
  const Step done = stepOnce(primaries);
  stepping_.store(false, std::memory_order_relaxed);
  return done;
}

template <class Real>
Step LogicalProcessor<Real>::stepOnce(int primaries) {
  if (transport_.terminated()) return Step::Terminated;
  if (locks_) return lockingStep(primaries);
  bool progressed = flushOverflow();
  const std::size_t n = transport_.receive(inbox_);
  for (std::size_t k = 0; k < n; ++k) onReceived(inbox_[k]);
  progressed |= n > 0;
  if (n == 0) progressed |= shootIfAllowed(primaries);
  reportBacklog();
  if (!progressed) return idleStep();
  publishProgress();
  return Step::Worked;
}

// 3.5.2 as the iPSC ran it (FifoFull::Lock): a send into a full FIFO locks the synthesis task until the
// FIFO has room. Only then does it finish the evaluation it was in (the rays it spawned here), take rays
// from its neighbours, one at a time so that a locked task takes none, and, when none came, shoot primaries.
template <class Real>
Step LogicalProcessor<Real>::lockingStep(int primaries) {
  bool progressed = sendHeld();
  if (!locked() && !local_.empty()) {
    evaluateLocalRays();
    progressed = true;
  }
  std::size_t n = 0;
  while (!locked() && n < inbox_.size() && transport_.receive(std::span<Message>(inbox_.data(), 1)) == 1) {
    onReceived(inbox_[0]);
    ++n;
  }
  progressed |= n > 0;
  if (n == 0 && !locked()) progressed |= shootIfAllowed(primaries);
  publishLock();
  reportBacklog();
  if (!progressed) return locked() ? Step::Waiting : idleStep();
  publishProgress();
  return Step::Worked;
}

template <class Real>
void LogicalProcessor<Real>::publishLock() {
  lockedOn_.store(locked() ? neighbours_[held_.front().first] : -1, std::memory_order_release);
}

// FifoFull::Lock: the held rays in the order they were sent, until one finds its FIFO still full.
template <class Real>
bool LogicalProcessor<Real>::sendHeld() {
  bool moved = false;
  while (!held_.empty()) {
    const auto& [slot, m] = held_.front();
    if (transport_.trySend(neighbours_[slot], std::span<const Message>(&m, 1)) != 1) break;
    countSent(slot, m);
    held_.pop_front();
    moved = true;
  }
  return moved;
}

// FifoFull::Lock: a send while locked waits behind the one that locked the task.
template <class Real>
void LogicalProcessor<Real>::sendOrLock(std::size_t slot, const Message& m) {
  if (held_.empty()) {
    if (transport_.trySend(neighbours_[slot], std::span<const Message>(&m, 1)) == 1)
      return countSent(slot, m);
    ++stats_.refusedPushes;
    ++stats_.locks;
  }
  held_.emplace_back(slot, m);
  stats_.overflowHighWater = std::max<std::uint64_t>(stats_.overflowHighWater, held_.size());
}

// Back-pressure (scheduling::kBacklogLimit, kMachineBacklogLimit): no new primary rays while rays wait for
// room, here or, where the transport sees it, across the machine.
template <class Real>
bool LogicalProcessor<Real>::primariesAllowed() const {
  return !locked() && backlog() < scheduling::kBacklogLimit && !transport_.primariesHeld();
}

// Up to `primaries` more primary rays, each as back-pressure allows; counts the steps that found the machine
// holding back their first.
template <class Real>
bool LogicalProcessor<Real>::shootIfAllowed(int primaries) {
  int shot = 0;
  while (shot < primaries && primariesLeft()) {
    if (!primariesAllowed()) {
      if (shot == 0) stats_.primariesHeld += transport_.primariesHeld();
      break;
    }
    shot += shootNextPrimary() ? 1 : 0;
  }
  return shot > 0;
}

template <class Real>
void LogicalProcessor<Real>::reportBacklog() {
  const std::size_t now = backlog();
  if (now != reportedBacklog_)
    transport_.countWaiting(std::ptrdiff_t(now) - std::ptrdiff_t(reportedBacklog_));
  reportedBacklog_ = now;
}

template <class Real>
void LogicalProcessor<Real>::publishProgress() {
  segmentsEvaluated_.store(stats_.processed.totalRays(), std::memory_order_relaxed);
  stepsWorked_.store(stepsWorked_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
}

template <class Real>
std::string LogicalProcessor<Real>::describeHeldWork() const {
  std::string held;
  auto add = [&](const std::string& what) { held += (held.empty() ? "" : ", ") + what; };
  const long long primaries = area_.count() * context_.view.raysPerSample() - nextPrimary_;
  if (primaries > 0) add(std::to_string(primaries) + " primary rays to shoot");
  if (!local_.empty()) add(std::to_string(local_.size()) + " rays of its own to trace");
  if (backlog() > 0) add(std::to_string(backlog()) + " rays waiting for room in a neighbour's FIFO");
  if (termination_.holdsToken()) add("the termination token");
  return held.empty() ? "nothing" : held;
}

template <class Real>
void LogicalProcessor<Real>::countToken() {
  stats_.tokenVisits = termination_.visits();
  stats_.tokenRounds = termination_.roundsStarted();
}

template <class Real>
bool LogicalProcessor<Real>::shootNextPrimary() {
  const int raysPerSample = context_.view.raysPerSample();
  if (nextPrimary_ >= area_.count() * raysPerSample) return false;
  const long long sample = nextPrimary_ / raysPerSample;
  const int k = int(nextPrimary_ % raysPerSample);
  const int sx = area_.x0 + int(sample % area_.width());
  const int sy = area_.y0 + int(sample / area_.width());
  ++nextPrimary_;
  ++stats_.spawned[std::size_t(core::RayKind::Eye)];
  // departing() would copy the eye ray from a temporary: built in place instead (see local_).
  Message m{.ray = core::eyeRayOf<Real>(context_.view, sx, sy, k), .destination = std::uint16_t(setup_.id)};
  m.tEnter = m.ray.ray.tMin;
  evaluate(m, true);
  evaluateLocalRays();
  return true;
}

// Rays spawned here that start in this region, depth first (keeps the local stack short).
template <class Real>
void LogicalProcessor<Real>::evaluateLocalRays() {
  while (!local_.empty() && !locked()) {  // a locked task resumes them once unlocked
    const Message next = departing(local_.back(), setup_.id);
    local_.pop_back();
    evaluate(next, false);
  }
}

namespace {

// The candidates of a cell of the paper's: every object it lists.
template <class Real, class Visit>
void forEachCandidate(const std::vector<std::uint32_t>& objects, const core::BasicRay<Real>&, double, double,
                      const Real&, core::TraceCounters&, Visit&& visit) {
  for (std::uint32_t object : objects)
    if (!visit(object)) return;
}

// The candidates of a region in a BVH: the objects whose boxes the ray meets in [ta, tb] (rounded outwards
// in Real), nearest first, no farther than tLimit.
template <class Real, class Visit>
void forEachCandidate(const core::BasicBvh<Real>& bvh, const core::BasicRay<Real>& ray, double ta, double,
                      const Real& tLimit, core::TraceCounters& counters, Visit&& visit) {
  bvh.traverse(ray, std::max(ray.tMin, core::roundedTowards<Real>(ta, -core::kInfinity)), tLimit, counters,
               visit);
}

}  // namespace

// Tests `objects` (a cell's list, or the region's BVH) for the part [ta, tb) of the ray's interval this
// cell owns. Closest-hit rays stop at the first interval holding a hit; light rays multiply the
// transmissions they cross and stop at an opaque one.
template <class Real>
template <class Objects>
bool LogicalProcessor<Real>::visitInterval(const TracedRay& ray, double ta, double tb, const Objects& objects,
                                           core::Hit& hit, double& transmission) {
  const core::Scene& scene = scene_;
  const double tLimit = ray.kind == core::RayKind::Light ? ray.ray.tMax : core::kInfinity;
  auto test = [&](std::uint32_t object) -> double {
    core::countTest(stats_.processed, scene.objects[object]);
    return core::nearestHit(scene.objects[object], ray.ray, tLimit);
  };
  // The paper's cells list an object in every cell it crosses: its answer is kept for the ray (a test memo);
  // a region's BVH offers each of its objects once.
  auto nearest = [&](std::uint32_t object) {
    if (object == ahead_.object) return ahead_.t;  // found by a region behind, beyond its part of the ray
    if (memoStamp_.empty()) return test(object);
    if (memoStamp_[object] != rayStamp_) {
      memoStamp_[object] = rayStamp_;
      memoT_[object] = test(object);
    }
    return memoT_[object];
  };
  // How far along the ray a candidate's box may start: the interval's end, then the best hit so far.
  Real bound = core::roundedTowards<Real>(std::min(tb, tLimit), core::kInfinity);
  if (ray.kind == core::RayKind::Light) {
    crossed_.clear();
    bool opaque = false;
    forEachCandidate(objects, ray.ray, ta, tb, bound, stats_.processed, [&](std::uint32_t object) {
      const double t = nearest(object);
      if (t < ta || t >= tb) return true;
      opaque = !shading_.transmissive(object);
      if (!opaque) crossed_.push_back(core::Hit{t, object});
      return !opaque;
    });
    if (opaque) {
      transmission = 0;
      return false;
    }
    if (!crossed_.empty()) transmission = core::transmissionThrough(transmission, crossed_, shading_);
    return transmission > 0;
  }
  forEachCandidate(objects, ray.ray, ta, tb, bound, stats_.processed, [&](std::uint32_t object) {
    const core::Hit h{nearest(object), object};
    if (h.t >= ta && h.t < tb) {
      if (h.closerThan(hit)) {
        hit = h;
        bound = core::roundedTowards<Real>(h.t, core::kInfinity);
      }
    } else if (carriesAhead_ && h.t >= tb &&
               (h.t < core::kInfinity ? h.closerThan(ahead_) : !ahead_.found())) {
      // Beyond this interval, or no hit at all (the first such object met, while no hit lies ahead): the
      // regions ahead need not test it again.
      ahead_ = h;
    }
    return true;
  });
  return !hit.found();
}

template <class Real>
void LogicalProcessor<Real>::newRayStamp() {
  if (++rayStamp_ == 0) {  // stamps wrapped: forget every memo
    std::fill(memoStamp_.begin(), memoStamp_.end(), 0u);
    rayStamp_ = 1;
  }
}

template <class Real>
void LogicalProcessor<Real>::locateEntryCell(const TracedRay& ray, const EyeFrameRay& er, double t,
                                             bool primary, int& column, int& row) const {
  if (primary) {
    cells_.locateSample(int(ray.sample % context_.view.samplesX()),
                        int(ray.sample / context_.view.samplesX()), column, row);
  } else {
    cells_.locate(er, t, column, row);
  }
}

// evaluate_ray of 3.5.2: follow the ray through this region's cells from where it entered; it ends here
// (hit, light reached, or escaped) or leaves through a face towards the processor whose region it enters.
template <class Real>
void LogicalProcessor<Real>::evaluate(const Message& m, bool primary) {
  const TracedRay& ray = m.ray;
  ++stats_.processed.of(ray.kind);
  newRayStamp();
  const EyeFrameRay er = EyeFrameRay::of(ray.ray, context_.view);
  if (ray.kind == core::RayKind::Light && m.tEnter == ray.ray.tMin && m.transmissionOrAheadT == 1)
    if (const LightSources* from = lightSourcesHolding(er.o))
      return finishRay(ray, core::Hit{}, traceWhereItStarts(ray, er, *from));
  const bool light = ray.kind == core::RayKind::Light;
  const double tMax = light ? ray.ray.tMax : core::kInfinity;
  core::Hit hit;
  double transmission = light ? m.transmissionOrAheadT : 1.0;
  ahead_ = carriesAhead_ && !light && m.ahead != kNothingAhead ? core::Hit{m.transmissionOrAheadT, m.ahead}
                                                               : core::Hit{};
  double t = m.tEnter;
  auto visit = [&](double ta, double tb, const std::vector<std::uint32_t>& objects) {
    return structure_ == CellStructure::Bvh ? visitInterval(ray, ta, tb, *regionBvh_, hit, transmission)
                                            : visitInterval(ray, ta, tb, objects, hit, transmission);
  };
  auto leaveFor = [&](int owner, double tExit) {
    if (beyondScene(ray.ray, tExit, tMax) ||
        (ahead_.t == core::kInfinity && nothingAhead(er, ray.ray, owner, tExit, tMax))) {
      ++stats_.leftScene;
      return finishRay(ray, hit, transmission);
    }
    send(Message{.ray = ray,
                 .tEnter = tExit,
                 .transmissionOrAheadT = light ? transmission : (ahead_.found() ? ahead_.t : 1.0),
                 .destination = std::uint16_t(owner),
                 .ahead = light ? kNothingAhead : ahead_.object});
  };
  // The ray's line has two parts, in front of the eye and behind it (EyeFrameRay::partEnd), so the walk
  // passes from one to the other at most once; a ray whose numbers are NaN, on which no part ever ends,
  // still ends here, having met what every test of NaN meets: nothing.
  for (int part = 0; part < kPartsOfALine; ++part) {
    const double tEnd = std::min(er.partEnd(t), tMax);
    if (!er.inFront(t)) {
      // Behind the eye plane: every node holds these objects, so the ray's rear part is traced right here.
      if ((t < tEnd && !visitInterval(ray, t, tEnd, setup_.rearObjects, hit, transmission)) ||
          er.lastPart(t, tMax))
        return finishRay(ray, hit, transmission);
      t = tEnd;
      // An eye ray is in its own pixel's pyramid wherever it is in front of the eye (3.1), however near the
      // apex rounding put its origin (a float eye ray from the eye itself, hither 0, may start just behind).
      if (primary) continue;
      if (const int owner = context_.regions.ownerAt(er, t); owner != setup_.id) return leaveFor(owner, t);
      continue;
    }
    int column, row;
    locateEntryCell(ray, er, t, primary, column, row);
    RegionExit exit;
    const WalkResult result = cells_.walk(er, t, tEnd, column, row, visit, exit, stats_.processed.cellSteps);
    if (result == WalkResult::Exited)
      return leaveFor(context_.regions.ownerBeyond(setup_.id, er, exit.t, exit.sStep, exit.qStep), exit.t);
    if (result == WalkResult::Stopped || er.lastPart(t, tMax)) return finishRay(ray, hit, transmission);
    t = tEnd;  // on to the rear part
  }
  finishRay(ray, hit, transmission);
}

// Whether the ray's part [t, tMax] misses every object of the scene: it leaves the scene's bounds for good.
// The boxes are padded well beyond any hit's rounding, so nothing ruled out could have been hit: the ray
// ends here as it would have ended at the screen's edge, regions later.
template <class Real>
bool LogicalProcessor<Real>::beyondScene(const core::BasicRay<Real>& ray, double t, double tMax) const {
  return !context_.sceneBounds.empty() &&
         !meetsBounds(context_.sceneBounds, core::Vec3(ray.origin), core::Vec3(ray.direction), t, tMax);
}

// Whether the ray, leaving for region `next` at t, misses the objects of every region it would cross on its
// way out of the scene (node/regions_ahead.h). Not asked of a closest-hit ray carrying a hit found ahead.
template <class Real>
bool LogicalProcessor<Real>::nothingAhead(const EyeFrameRay& er, const core::BasicRay<Real>& ray, int next,
                                          double t, double tMax) const {
  return node::nothingAhead(context_.regions, context_.regionBounds, context_.sceneBounds, er,
                            core::Vec3(ray.origin), core::Vec3(ray.direction), next, t, tMax);
}

// 3.7.2: a light ray born in this region, from a point of the light-source box, meets only the objects of
// its light's volume, all held here: traced in one piece, exactly as the reference traces it; no message.
// `origin`: the ray's origin in the eye frame (EyeFrameRay::o).
template <class Real>
const LightSources* LogicalProcessor<Real>::lightSourcesHolding(const core::Vec3& origin) const {
  if (setup_.lightRays == LightRayMode::Messages) return nullptr;
  auto inside = [&](const core::Box& box) {
    for (int a = 0; a < 3; ++a)
      if (!(origin[a] >= box.lo[a] && origin[a] <= box.hi[a])) return false;
    return true;
  };
  if (inside(setup_.lightSources.eyeBox)) return &setup_.lightSources;
  return inside(setup_.rearLightSources.eyeBox) ? &setup_.rearLightSources : nullptr;
}

// Its transmission (a light ray that starts in the light-source box `from`): in the paper's cells of its
// light's volume, or in the tree over what the processor holds (with the shadow cache).
template <class Real>
double LogicalProcessor<Real>::traceWhereItStarts(const TracedRay& ray, const EyeFrameRay& er,
                                                  const LightSources& from) {
  ++stats_.lightRaysTracedLocally;
  if (walksLightCells()) return walkLightVolume(ray, er, from);
  return core::lightRayTransmission(shading_, *lightRayTree_, ray, stats_.processed, lightRayScratch_);
}

// The paper's cells for a light ray traced where it starts (3.3, 3.7.2): the region's own super-cells, its
// outermost faces pushed to infinity, listing its light's volume's objects and cut by their depths, walked
// as evaluate() walks the region's, with the same interval rule and test memos. Beyond the region's pixel
// area the outer columns are wide: a light cone's extra objects there are more depth cuts and tests than a
// light pyramid's. No shadow cache: a light-ray message has none, and a cached blocker tested over the
// whole ray may hit where no cell lists it (a scene of 1e38 scale ratios), its answer then depending on
// the rays traced before.
template <class Real>
double LogicalProcessor<Real>::walkLightVolume(const TracedRay& ray, const EyeFrameRay& er,
                                               const LightSources& from) {
  newRayStamp();
  ahead_ = core::Hit{};  // the ray that spawned it is done
  const int source = &from == &setup_.lightSources ? 0 : 1;
  const RegionCells& cells = lightCells_[source][ray.light];
  const std::vector<std::uint32_t>& rear = lightRearObjects_[source][ray.light];
  core::Hit hit;  // a light ray finds none: it multiplies transmissions
  double transmission = 1, t = ray.ray.tMin;
  const double tMax = ray.ray.tMax;
  auto visit = [&](double ta, double tb, const std::vector<std::uint32_t>& objects) {
    return visitInterval(ray, ta, tb, objects, hit, transmission);
  };
  for (int part = 0; part < kPartsOfALine; ++part) {
    const double tEnd = std::min(er.partEnd(t), tMax);
    if (!er.inFront(t)) {
      if ((t < tEnd && !visit(t, tEnd, rear)) || er.lastPart(t, tMax)) return transmission;
      t = tEnd;
      continue;
    }
    int column, row;
    cells.locate(er, t, column, row);
    RegionExit exit;
    // The cells cover all the space in front of the eye: the walk leaves them only on a NaN, having met what
    // every test of NaN meets, nothing.
    const WalkResult result = cells.walk(er, t, tEnd, column, row, visit, exit, stats_.processed.cellSteps);
    if (result == WalkResult::Stopped || er.lastPart(t, tMax)) return transmission;
    t = tEnd;
  }
  return transmission;
}

template <class Real>
void LogicalProcessor<Real>::finishRay(const TracedRay& ray, const core::Hit& hit, double transmission) {
  shade(ray, hit, transmission, outcome_);
  deliver(outcome_);
}

// The ray ends here: its contributions and the rays it spawns, into `outcome`.
template <class Real>
void LogicalProcessor<Real>::shade(const TracedRay& ray, const core::Hit& hit, double transmission,
                                   core::BasicRayOutcome<Real>& outcome) {
  ++stats_.finished[std::size_t(ray.kind)];
  outcome.clear();
  if (ray.kind == core::RayKind::Light)
    shading_.finishLightRay(ray, transmission, outcome);
  else if (hit.found())
    shading_.shadeHit(ray, hit, outcome);
  else
    shading_.shadeMiss(ray, outcome);
}

// 3.4: contributions go straight to the host; new rays start where they are born. A light ray born here
// in the light-source box is traced at once (3.7.2), as it would be when its turn came on the local stack:
// the same processor, the same tests and contribution, without becoming a message first.
template <class Real>
void LogicalProcessor<Real>::deliver(const core::BasicRayOutcome<Real>& outcome) {
  shipContributions(outcome);
  for (const TracedRay& spawned : outcome.spawned) {
    ++stats_.spawned[std::size_t(spawned.kind)];
    const double tEnter = spawned.ray.tMin;
    const EyeFrameRay er = EyeFrameRay::of(spawned.ray, context_.view);
    const int owner = !er.inFront(tEnter) || context_.regions.holds(setup_.id, er, tEnter)
                          ? setup_.id
                          : context_.regions.ownerAt(er, tEnter);
    if (owner != setup_.id) {
      send(departing(spawned, owner));
    } else if (const LightSources* from =
                   spawned.kind == core::RayKind::Light ? lightSourcesHolding(er.o) : nullptr) {
      ++stats_.processed.of(spawned.kind);
      shade(spawned, core::Hit{}, traceWhereItStarts(spawned, er, *from), lightOutcome_);
      shipContributions(lightOutcome_);  // a light ray spawns nothing
    } else {
      local_.push_back(spawned);
    }
  }
}

template <class Real>
void LogicalProcessor<Real>::shipContributions(const core::BasicRayOutcome<Real>& outcome) {
  for (const core::Contribution& c : outcome.contributions) {
    ++stats_.processed.contributions;
    if (!std::isfinite(c.value.x + c.value.y + c.value.z)) ++stats_.processed.nonFinite;
    transport_.sendContribution(c);
  }
}

// Communication task: never block on a full FIFO (the paper's deadlock, 2.2): keep the ray in a local
// overflow list, in order, and go on consuming incoming rays, so a cycle of full queues always drains.
template <class Real>
void LogicalProcessor<Real>::send(Message m) {
  const int hop = context_.regions.nextHop(setup_.id, m.destination);
  const std::size_t slot = slotOf(hop);
  m.face = std::uint8_t(opposite(faceOf_[slot]));
  if (locks_) return sendOrLock(slot, m);
  OverflowList<Message>& pending = overflow_[slot];
  if (pending.empty() && transport_.trySend(hop, std::span<const Message>(&m, 1)) == 1) {
    countSent(slot, m);
    return;
  }
  ++stats_.refusedPushes;
  pending.push_back(m);
  stats_.overflowHighWater = std::max<std::uint64_t>(stats_.overflowHighWater, pending.size());
}

template <class Real>
std::size_t LogicalProcessor<Real>::slotOf(int neighbour) const {
  return context_.regions.neighbourSlot(setup_.id, neighbour);
}

template <class Real>
void LogicalProcessor<Real>::countSent(std::size_t slot, const Message& m) {
  termination_.countSent();
  ++stats_.sent[std::size_t(faceOf_[slot])];
  ++stats_.messagesByKind[std::size_t(m.ray.kind)];
}

template <class Real>
bool LogicalProcessor<Real>::flushOverflow() {
  bool moved = false;
  for (std::size_t slot = 0; slot < overflow_.size(); ++slot) {
    OverflowList<Message>& pending = overflow_[slot];
    while (!pending.empty()) {  // the oldest first, a chunk's run at a time, until the FIFO is full
      const std::span<const Message> waiting = pending.oldest();
      const std::size_t n = transport_.trySend(neighbours_[slot], waiting);
      for (std::size_t k = 0; k < n; ++k) countSent(slot, waiting[k]);
      pending.pop_front(n);
      moved |= n > 0;
      if (n < waiting.size()) break;
    }
  }
  return moved;
}

template <class Real>
void LogicalProcessor<Real>::onReceived(const Message& m) {
  termination_.countReceived();
  ++stats_.received[m.face];
  if (m.destination != setup_.id) {
    ++stats_.forwarded;
    send(m);
    return;
  }
  evaluate(m, false);
  evaluateLocalRays();
}

template <class Real>
std::size_t LogicalProcessor<Real>::backlog() const {
  std::size_t waiting = 0;
  for (const auto& pending : overflow_) waiting += pending.size();
  return waiting + held_.size();
}

template <class Real>
bool LogicalProcessor<Real>::primariesLeft() const {
  return nextPrimary_ < area_.count() * context_.view.raysPerSample();
}

template <class Real>
bool LogicalProcessor<Real>::passive() const {
  if (primariesLeft() || !local_.empty() || locked()) return false;
  for (const auto& pending : overflow_)
    if (!pending.empty()) return false;
  return true;
}

// Termination (3.6) with Safra's counting token (see SafraTermination). The paper's second phase is kept: a
// node touches the token only once its primary rays are done and it has nothing to do.
template <class Real>
Step LogicalProcessor<Real>::idleStep() {
  transport_.flushContributions();
  if (Token token; !termination_.holdsToken() && transport_.receiveToken(token)) {
    termination_.takeToken(token);
    countToken();
  }
  if (!termination_.holdsToken() || !passive()) return Step::Waiting;
  const SafraTermination::Decision decision = termination_.release();
  countToken();
  if (decision == SafraTermination::Decision::AnnounceTermination)
    transport_.announceTermination();
  else
    transport_.passToken(termination_.token());
  return Step::Worked;
}

template <class Real>
bool LogicalProcessor<Real>::readyToStep() const {
  if (transport_.terminated()) return true;
  if (locked()) return transport_.canSend(neighbours_[held_.front().first]);  // nothing else moves it
  if (transport_.anyIncoming()) return true;
  if (primariesLeft() && primariesAllowed()) return true;  // held back by the machine, and now let go
  for (std::size_t slot = 0; slot < overflow_.size(); ++slot)
    if (!overflow_[slot].empty() && transport_.canSend(neighbours_[slot])) return true;
  return !termination_.holdsToken() && transport_.hasToken();
}

template class LogicalProcessor<float>;
template class LogicalProcessor<double>;

}  // namespace raycube::node
