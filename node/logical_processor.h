#pragma once
// One processor of the machine (Priol & Bouatouch 3.5.2): a synthesis task that shoots the primary rays of
// its pixel area and evaluates every ray that reaches its region, interleaved in one thread with a
// communication task that moves rays through the face FIFOs, ships contributions to the host and passes
// the termination token.
#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/bvh.h"
#include "core/intersect.h"
#include "core/ray_tree.h"
#include "core/trace_stats.h"
#include "core/view.h"
#include "core/whitted.h"
#include "node/database_bvh.h"
#include "node/light_sources.h"
#include "node/machine_context.h"
#include "node/overflow_list.h"
#include "node/region_cells.h"
#include "node/region_database.h"
#include "node/region_map.h"
#include "node/safra_termination.h"
#include "node/transport.h"

namespace raycube::node {

// What the host hands a processor (3.2 steps 1-2): its place, its pixel area, its pruned objects. Every
// object list holds indices into `database`'s traced() scene, which processors holding the same objects share
// (an engine sending a setup to another address space sends the database's value).
struct NodeSetup {
  int id = 0;
  CellStructure cells = CellStructure::Auto;       // the paper's cells or a BVH (Auto: a BVH, chosenFor)
  int cellLevel = 2;                               // recursive halvings of the pixel area (super-cells)
  std::shared_ptr<const RegionDatabase> database;  // the only objects this processor holds
  std::vector<std::uint32_t> objects;              // objects touching the region (pruned by the host)
  std::vector<EyeBox> objectBoxes;         // the eye box of each of `objects`: the cells are cut from them
  std::vector<std::uint32_t> rearObjects;  // objects reaching behind the eye plane, held by every node
  // 3.7.2: with light cones or pyramids, the eye-frame box this region's light rays start in; the database
  // holds every object their light volumes meet, and such rays are traced where they start; light rays
  // starting elsewhere travel as messages.
  LightRayMode lightRays = LightRayMode::Messages;
  // With the paper's cells, whether such rays walk cells of their light's volume (the host gives each
  // light's volume in the light sources) rather than a tree over what the processor holds: the emulated
  // machine's choice, whose costs count what the walk meets. On thousands of objects the volumes' depth cuts
  // explode (gears 4 at 32x32 on 4x4: 0.6 s became 31 s and 0.9 GB), so real cores keep the tree.
  bool lightRaysWalkCells = false;
  LightSources lightSources;
  // The same for light rays starting behind the eye (on a rear object), identical for every processor.
  LightSources rearLightSources;
  // What the host found for the report: the light volumes' objects summed over the lights, and how many of
  // those are not among the region's objects.
  std::size_t lightObjects = 0, extraLightObjects = 0;
  // The shape of the host's BVH over the whole scene, where the host shares this address space: the BVHs
  // over the processor's database and its region keep it, restricted to what they hold, instead of being
  // built anew (node/database_bvh.h). None across address spaces (an MPI rank builds its own), nor when
  // emulating, whose costs count box tests.
  std::shared_ptr<const core::BvhShape> sceneShape;
  // The host's BVH over the whole scene, for processors reading it in place: their light rays traced where
  // they start use it (LightRayTree). None where sceneShape is none.
  std::shared_ptr<const SceneTree> sceneTree;
};

struct NodeStats {
  int id = 0;
  SampleRect area;
  std::size_t objects = 0, rearObjects = 0, cells = 0;
  bool bvh = false;                   // the region's objects in a BVH rather than the paper's cells
  std::size_t heldObjects = 0;        // the region database: region, rear and light-volume objects
  std::size_t lightObjects = 0;       // objects held for light rays (summed over lights)
  std::size_t extraLightObjects = 0;  // of those, objects not already in the region's cells
  std::uint64_t lightRaysTracedLocally = 0;
  core::TraceCounters processed;  // ray segments evaluated here, by kind; tests; cell steps
  std::array<std::uint64_t, core::kRayKinds> spawned{};         // rays created here (eye rays and shading)
  std::array<std::uint64_t, core::kRayKinds> finished{};        // rays whose evaluation ended here
  std::array<std::uint64_t, core::kRayKinds> messagesByKind{};  // rays sent to a neighbour, by kind
  std::array<std::uint64_t, kFaces> sent{}, received{};
  std::uint64_t forwarded = 0;      // messages passed on towards a non-adjacent destination (hops)
  std::uint64_t leftScene = 0;      // rays ended as they left their region, nothing ahead (regions_ahead.h)
  std::uint64_t refusedPushes = 0;  // sends that found the neighbour's FIFO full
  std::uint64_t primariesHeld = 0;  // steps with primaries left that found the machine holding them back
  std::uint64_t overflowHighWater = 0;
  std::uint64_t locks = 0;  // FifoFull::Lock: times the synthesis task locked on a full FIFO (3.5.2)
  std::uint64_t tokenVisits = 0;
  std::uint32_t tokenRounds = 0;  // node 0: token rounds started
};

// What one step did: some work (rays, the token), nothing because the node waits for the interconnect, or
// nothing because the machine has terminated.
enum class Step : std::uint8_t { Worked, Waiting, Terminated };

// Real: the precision of the rays it traces and sends (--precision); its walk through cells is in double.
// The node is stepped by a driver (a thread, a SimGrid actor, an MPI rank) that owns waiting and the clock:
// step() until it returns Waiting, then wait until readyToStep() (or blocked() says why it waits).
template <class Real>
class LogicalProcessor {
 public:
  using Message = BasicRayMessage<Real>;
  using TracedRay = core::BasicTracedRay<Real>;
  LogicalProcessor(const MachineContext& context, NodeSetup setup, BasicTransport<Real>& transport);

  // primaries: how many primary rays the step may shoot when no ray arrived (one, as the paper's synthesis
  // task, where a driver's clock charges each step; more where steps cost only their bookkeeping).
  Step step(int primaries = 1);
  // Something arrived that the next step would act on: a ray, room in a FIFO it has rays for, the token,
  // or termination. Reads only the transport's state: a driver may call it from a wait predicate.
  bool readyToStep() const;
  // Waiting on full neighbour FIFOs (3.6's locked processors), not merely idle.
  bool blocked() const { return backlog() > 0; }
  // FifoFull::Lock: the processor whose full FIFO the synthesis task is locked on, or -1. Safe to read from
  // another thread (the deadlock watch), as are stepsWorked(), steps that did anything (shot, received,
  // evaluated or sent a ray) so far, and stepping(), whether a step is under way now (the stall watch,
  // host/engines/stall_watch.h).
  int lockedOn() const { return lockedOn_.load(std::memory_order_acquire); }
  std::uint64_t stepsWorked() const { return stepsWorked_.load(std::memory_order_acquire); }
  bool stepping() const { return stepping_.load(std::memory_order_relaxed); }
  // Counted so far; read between steps (a driver charges simulated time from it after every step).
  const NodeStats& stats() const { return stats_; }
  // Ray segments evaluated here (stats().processed.totalRays()) as of the last step that worked; safe to
  // read from another thread: the host's progress.
  std::uint64_t segmentsEvaluated() const { return segmentsEvaluated_.load(std::memory_order_relaxed); }
  // What the processor still holds (primaries, local rays, rays for full FIFOs, the token), for the error
  // a stalled machine ends with; read once its driver has stopped stepping it.
  std::string describeHeldWork() const;

 private:
  // Synthesis task
  bool shootNextPrimary();
  bool primariesLeft() const;
  bool primariesAllowed() const;
  bool shootIfAllowed(int primaries);
  void evaluate(const Message& message, bool primary);
  // A stamp no memo holds yet: the objects this ray tests are tested once each (3.3).
  void newRayStamp();
  // The cell the ray's front part starts in: an eye ray's pixel, any other ray's point at t.
  void locateEntryCell(const TracedRay& ray, const EyeFrameRay& er, double t, bool primary, int& column,
                       int& row) const;
  void evaluateLocalRays();
  void finishRay(const TracedRay& ray, const core::Hit& hit, double transmission);
  void shade(const TracedRay& ray, const core::Hit& hit, double transmission,
             core::BasicRayOutcome<Real>& outcome);
  // 3.7.2: the light sources (the region's or the rear's) whose box holds a light ray's origin in the eye
  // frame, or none: the ray is traced where it starts only from there.
  const LightSources* lightSourcesHolding(const core::Vec3& eyeFrameOrigin) const;
  double traceWhereItStarts(const TracedRay& ray, const EyeFrameRay& er, const LightSources& from);
  double walkLightVolume(const TracedRay& ray, const EyeFrameRay& er, const LightSources& from);
  bool walksLightCells() const { return setup_.lightRaysWalkCells && structure_ == CellStructure::Paper; }
  bool beyondScene(const core::BasicRay<Real>& ray, double t, double tMax) const;
  bool nothingAhead(const EyeFrameRay& er, const core::BasicRay<Real>& ray, int next, double t,
                    double tMax) const;
  template <class Objects>
  bool visitInterval(const TracedRay& ray, double ta, double tb, const Objects& objects, core::Hit& hit,
                     double& transmission);
  void deliver(const core::BasicRayOutcome<Real>& outcome);
  void shipContributions(const core::BasicRayOutcome<Real>& outcome);
  // FifoFull::Lock (3.5.2)
  Step lockingStep(int primaries);
  bool locked() const { return !held_.empty(); }
  void sendOrLock(std::size_t slot, const Message& message);
  bool sendHeld();
  void publishLock();
  // Communication task
  void send(Message message);
  void countSent(std::size_t slot, const Message& message);
  std::size_t slotOf(int neighbour) const;
  bool flushOverflow();
  void onReceived(const Message& message);
  Step stepOnce(int primaries);
  Step idleStep();
  void countToken();  // the token's visits and rounds into stats_
  void publishProgress();
  bool passive() const;
  std::size_t backlog() const;  // rays waiting for room in a neighbour's FIFO
  void reportBacklog();         // its change since the last report, to the transport

  const MachineContext& context_;
  NodeSetup setup_;
  const core::Scene& scene_;  // the region's database: its copy or the host's scene (RegionDatabase::traced)
  core::Whitted shading_;
  BasicTransport<Real>& transport_;
  SampleRect area_;
  CellStructure structure_;  // Paper or Bvh
  RegionCells cells_;
  // Every object the processor holds, in one tree, for light rays traced where they start (3.7.2), in BVH
  // regions. Holding more than a query needs costs it nothing but box tests: an object off a light ray's
  // segment never has a hit on it.
  std::optional<LightRayTree<Real>> lightRayTree_;
  // With NodeSetup::lightRaysWalkCells those light rays walk cells instead (3.3): per light volume (the
  // region's sources, then the rear's; light by light), the region's super-cells with their outer faces at
  // infinity, listing the volume's objects and cut by their depths; behind the eye plane, the volume's
  // objects reaching there.
  std::array<std::vector<RegionCells>, 2> lightCells_;
  std::array<std::vector<std::vector<std::uint32_t>>, 2> lightRearObjects_;
  // With CellStructure::Bvh, the region's own objects, the only ones a hit inside the region can be on.
  std::unique_ptr<const core::BasicBvh<Real>> regionBvh_;
  long long nextPrimary_ = 0;
  std::size_t reportedBacklog_ = 0;                  // backlog() as last told the transport (countWaiting)
  std::atomic<std::uint64_t> segmentsEvaluated_{0};  // written by this node only, once per step that worked
  std::atomic<bool> stepping_{false};                // inside step()
  // Rays spawned here that start in this region, still to evaluate here: not messages, so that the message
  // each becomes is built field by field where evaluate reads it. A message built so and then copied whole
  // is read in 16-byte pieces before its narrower stores have left the store buffer, and waits for them:
  // a large part of deliver's time when the local stack held messages.
  std::vector<TracedRay> local_;
  const std::vector<int>& neighbours_;           // processors across this region's faces
  std::vector<OverflowList<Message>> overflow_;  // per neighbour: rays its full FIFO refused
  const std::vector<Face> faceOf_;               // per neighbour: the face of this region it lies across
  std::vector<Message> inbox_;
  // FifoFull::Lock: the rays the locked synthesis task is sending, in the order it sent them, with their
  // neighbour's slot: the first waits for room in a full FIFO, the others (the rest of the evaluation it
  // was in: a few rays at most) behind it. Empty when not locked, and always with FifoFull::Overflow.
  const bool locks_;
  std::deque<std::pair<std::size_t, Message>> held_;
  std::atomic<int> lockedOn_{-1};
  std::atomic<std::uint64_t> stepsWorked_{0};
  core::BasicRayOutcome<Real> outcome_;
  core::BasicRayOutcome<Real>
      lightOutcome_;  // a light ray's, traced while outcome_'s spawned rays are delivered
  // Test memos (the "mailboxes" of the ray-tracing literature), with the paper's cells: an object met again
  // in a later cell of the same ray is not tested again. The cached t is the object's nearest hit over the
  // whole ray, the very number the reference renderer computes. Only up to the largest index the walk can
  // meet (a processor reading the whole scene in place would otherwise hold 12 bytes per scene object, even
  // in an empty region), and none with a BVH, which needs none.
  std::vector<std::uint32_t> memoStamp_;
  std::vector<double> memoT_;
  std::uint32_t rayStamp_ = 0;
  // The ray being evaluated (closest-hit rays, in BVH regions): the nearest hit found beyond the parts of
  // it visited so far, on an object a region ahead may meet again (BasicRayMessage::ahead). Only where the
  // processors read the host's scene in place, whose indices are the same in every region (a database's
  // copy numbers its objects its own way); the paper's cells keep the paper's per-region test memos only,
  // so the emulated machine's counts stay as fitted.
  core::Hit ahead_;
  const bool carriesAhead_;
  std::vector<core::Hit> crossed_;
  core::BasicRayTreeScratch<Real> lightRayScratch_;  // the shadow cache of light rays traced where they start
  SafraTermination termination_;
  NodeStats stats_;
};

}  // namespace raycube::node
