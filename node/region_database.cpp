#include "node/region_database.h"

#include <algorithm>

namespace raycube::node {
namespace {

// Everything of the scene but its objects.
core::Scene withoutObjects(const core::Scene& scene) {
  core::Scene s;
  s.name = scene.name;
  s.source = scene.source;
  s.camera = scene.camera;
  s.background = scene.background;
  s.lights = scene.lights;
  s.materials = scene.materials;
  return s;
}

}  // namespace

std::vector<std::uint32_t> heldObjectsOf(ObjectLists lists) {
  std::vector<std::uint32_t> held;
  for (const std::vector<std::uint32_t>* list : lists) held.insert(held.end(), list->begin(), list->end());
  std::sort(held.begin(), held.end());
  held.erase(std::unique(held.begin(), held.end()), held.end());
  return held;
}

RegionDatabase regionDatabaseOf(const core::Scene& scene, const std::vector<EyeBox>& eyeBoxes,
                                std::vector<std::uint32_t> held) {
  RegionDatabase db;
  db.scene = withoutObjects(scene);
  db.scene.objects.reserve(held.size());
  db.eyeBoxes.reserve(held.size());
  for (std::uint32_t g : held) {
    db.scene.objects.push_back(scene.objects[g]);
    db.eyeBoxes.push_back(eyeBoxes[g]);
  }
  db.globalIds = std::move(held);
  return db;
}

void toLocalIndices(const RegionDatabase& database, ObjectLists lists) {
  const std::vector<std::uint32_t>& ids = database.globalIds;
  for (std::vector<std::uint32_t>* list : lists)
    for (std::uint32_t& o : *list) o = std::uint32_t(std::lower_bound(ids.begin(), ids.end(), o) - ids.begin());
}

RegionDatabase gatherRegionDatabase(const core::Scene& scene, const std::vector<EyeBox>& eyeBoxes,
                                    ObjectLists lists) {
  RegionDatabase db = regionDatabaseOf(scene, eyeBoxes, heldObjectsOf(lists));
  toLocalIndices(db, lists);
  return db;
}

}  // namespace raycube::node
