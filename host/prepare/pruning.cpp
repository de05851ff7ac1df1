#include "host/prepare/pruning.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "core/intersect.h"
#include "core/tolerances.h"
#include "host/prepare/light_volume.h"
#include "host/util/parallel_for.h"
#include "node/scheduling.h"

namespace raycube::host {
namespace {

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

// The lists a processor's cells index, rewritten into its database's local indices: its region's, the
// rear's and, with the paper's cells, its light volumes'.
std::vector<std::vector<std::uint32_t>*> cellListsOf(node::NodeSetup& setup) {
  std::vector<std::vector<std::uint32_t>*> lists{&setup.objects, &setup.rearObjects};
  for (node::LightSources* sources : {&setup.lightSources, &setup.rearLightSources})
    for (std::vector<std::uint32_t>& objects : sources->volumeObjects) lists.push_back(&objects);
  return lists;
}

// The paper's cells (3.3) are cut from eye boxes: those of each light volume's objects (global indices).
void giveVolumeBoxes(node::LightSources& sources, const std::vector<node::EyeBox>& boxes) {
  sources.volumeBoxes.clear();
  for (const std::vector<std::uint32_t>& objects : sources.volumeObjects)
    sources.volumeBoxes.push_back(node::eyeBoxesOf(boxes, objects));
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
  auto bySet = [](const std::vector<std::uint32_t>* a, const std::vector<std::uint32_t>* b) {
    return *a < *b;
  };
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
    for (node::LightSources* sources : {&setup.lightSources, &setup.rearLightSources})
      giveVolumeBoxes(*sources, boxes);
    node::toLocalIndices(*setup.database, cellListsOf(setup));
  });
}

}  // namespace

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
    setup.cells = cellsFor(machine);
    setup.cellLevel = machine.cellLevel;
    setup.rearObjects = rear;
    setup.objects = inEyeFrame.query([&](const core::Box& b) {
      return node::mayTouch(node::EyeBox{b.lo, b.hi}, region);
    });
    if (!regionBounds.empty())
      regionBounds[std::size_t(p)] = regionBoundsOf(setup.objects, worldBoxesForBounds);
    setup.lightRays = machine.lightRays;
    // The light volumes' objects only decide what the processor holds: its database's BVH finds them.
    std::vector<std::vector<std::uint32_t>*> held{&setup.objects, &setup.rearObjects};
    std::vector<std::vector<std::uint32_t>> lightObjects;
    if (lightVolumes) {
      setup.lightSources = lightSourcesOf(region, setup.objects, boxes, view);
      for (const core::Light& light : scene.lights)
        lightObjects.push_back(
            objectsInLightVolume(machine.lightRays, light.position, setup.lightSources, inWorld));
      setup.rearLightSources = rearSources;
      countLightObjects(lightObjects, setup);
      for (auto* lists : {&lightObjects, &rearLightObjects})
        for (std::vector<std::uint32_t>& objects : *lists) held.push_back(&objects);
    }
    heldBy[std::size_t(p)] = node::heldObjectsOf(held, scene.objects.size());
    // With the paper's cells in emulated time the light rays traced where they start walk cells of their
    // light's volume's objects (3.3, 3.7.2): the processor keeps the lists. Elsewhere a tree over the
    // database finds them (node::NodeSetup::lightRaysWalkCells).
    setup.lightRaysWalkCells = lightVolumes && setup.cells == node::CellStructure::Paper && machine.emulate;
    if (setup.lightRaysWalkCells) {
      setup.lightSources.volumeObjects = std::move(lightObjects);
      setup.rearLightSources.volumeObjects = rearLightObjects;
    }
    if (holdsWholeScene(heldBy[std::size_t(p)], scene, machine)) heldBy[std::size_t(p)] = everyObject;
    setups[std::size_t(p)] = std::move(setup);
  });
  giveDatabases(setups, heldBy, scene, boxes, readsSceneInPlace(machine));
  return {std::move(setups), std::move(regionBounds)};
}

}  // namespace raycube::host
