#pragma once
// What a processor holds of the database (Priol & Bouatouch 3.2 step 1): only the objects its region, the
// rear space and its light volumes need. Across address spaces (an MPI rank) and on the emulated machine, a
// copy of them out of the scene with the scene's materials, lights, camera and background: a plain value the
// host sends to its node, local object i being global object globalIds[i] (local order is global order, so
// every tie between hits, "the lower index wins", is decided exactly as in the whole scene). Processors
// sharing the host's address space read the host's scene in place instead, by global index: the same
// objects reached the same way (the trees over them name only the held ones), without tens of thousands
// of copies of 144 bytes at 8 x 8.
#include <cstdint>
#include <span>
#include <vector>

#include "core/scene.h"
#include "node/eye_box.h"

namespace raycube::node {

struct RegionDatabase {
  core::Scene scene;                     // a copy: the held objects, in ascending global index order
  const core::Scene* inPlace = nullptr;  // or the host's whole scene, read in place (it outlives the run)
  core::SceneFeatures inPlaceFeatures;   // that scene's, worked out once for every processor
  std::vector<std::uint32_t> globalIds;  // the held objects' global indices, ascending
  std::size_t size() const { return globalIds.size(); }
  // The scene the processor traces, whose object indices its lists hold: local (a copy) or global (in place).
  const core::Scene& traced() const { return inPlace ? *inPlace : scene; }
  core::SceneFeatures features() const { return inPlace ? inPlaceFeatures : scene.features(); }
  // The held objects as indices into traced().
  std::vector<std::uint32_t> heldIndices() const;
  // Where traced()'s objects sit in the whole scene (core::BasicBvh's wholeIdOf): globalIds for a copy;
  // none, the same index, in place.
  std::span<const std::uint32_t> wholeIdOf() const {
    return inPlace ? std::span<const std::uint32_t>{} : std::span<const std::uint32_t>(globalIds);
  }
};

using ObjectLists = std::span<std::vector<std::uint32_t>* const>;

// Every object named in `lists` (global indices below sceneObjects), ascending and once each: what a
// processor holds.
std::vector<std::uint32_t> heldObjectsOf(ObjectLists lists, std::size_t sceneObjects);
// The database of the objects `held` (ascending global indices into `scene`): their copy.
RegionDatabase regionDatabaseOf(const core::Scene& scene, std::vector<std::uint32_t> held);
// The same objects read in place, in `scene` (whose features() are `features`), which must outlive the
// database.
RegionDatabase regionDatabaseIn(const core::Scene& scene, const core::SceneFeatures& features,
                                std::vector<std::uint32_t> held);
// Rewrites each list, of global indices all held by `database`, into the indices of its traced() scene (a
// copy's local indices; in place, unchanged).
void toLocalIndices(const RegionDatabase& database, ObjectLists lists);

// The database holding every object named in `lists` (global indices into `scene`); rewrites each list in
// place into local indices of that database.
RegionDatabase gatherRegionDatabase(const core::Scene& scene, ObjectLists lists);

// The eye boxes of `objects` (indices into `eyeBoxes`), in their order: what a processor cuts its cells from
// (node/region_cells.h), given with its region's objects rather than held per copy in the database.
std::vector<EyeBox> eyeBoxesOf(const std::vector<EyeBox>& eyeBoxes,
                               const std::vector<std::uint32_t>& objects);

}  // namespace raycube::node
