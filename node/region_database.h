#pragma once
// What a processor holds of the database (Priol & Bouatouch 3.2 step 1): only the objects its region, the
// rear space and its light volumes need, copied out of the scene with the scene's materials, lights, camera
// and background. A plain value, so a host can send it to a node in another address space (an MPI rank).
// Local object i is global object globalIds[i]; local order is global order, so every tie between hits
// ("the lower index wins") is decided exactly as in the whole scene.
#include <cstdint>
#include <span>
#include <vector>

#include "core/scene.h"
#include "node/eye_box.h"

namespace raycube::node {

struct RegionDatabase {
  core::Scene scene;                       // the held objects, in ascending global index order
  std::vector<std::uint32_t> globalIds;    // per local object
  std::size_t size() const { return globalIds.size(); }
};

using ObjectLists = std::span<std::vector<std::uint32_t>* const>;

// Every object named in `lists` (global indices below sceneObjects), ascending and once each: what a
// processor holds.
std::vector<std::uint32_t> heldObjectsOf(ObjectLists lists, std::size_t sceneObjects);
// The database of the objects `held` (ascending global indices into `scene`).
RegionDatabase regionDatabaseOf(const core::Scene& scene, std::vector<std::uint32_t> held);
// Rewrites each list, of global indices all held by `database`, into its local indices.
void toLocalIndices(const RegionDatabase& database, ObjectLists lists);

// The database holding every object named in `lists` (global indices into `scene`); rewrites each list in
// place into local indices of that database.
RegionDatabase gatherRegionDatabase(const core::Scene& scene, ObjectLists lists);

// The eye boxes of `objects` (indices into `eyeBoxes`), in their order: what a processor cuts its cells from
// (node/region_cells.h), given with its region's objects rather than held per copy in the database.
std::vector<EyeBox> eyeBoxesOf(const std::vector<EyeBox>& eyeBoxes,
                               const std::vector<std::uint32_t>& objects);

}  // namespace raycube::node
