#include "node/region_database.h"

#include <algorithm>
#include <iterator>

#include "core/bvh.h"

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

std::vector<std::uint32_t> heldObjectsOf(ObjectLists lists, std::size_t sceneObjects) {
  // Short ascending lists (the host's spatial queries give them so) merge in their length, where a flag per
  // scene object costs the whole scene for each of 64 processors; long ones take the flags.
  auto ascending = [](const std::vector<std::uint32_t>* list) {
    return std::is_sorted(list->begin(), list->end());
  };
  std::size_t named = 0;
  for (const std::vector<std::uint32_t>* list : lists) named += list->size();
  if (named < sceneObjects / 8 && std::all_of(lists.begin(), lists.end(), ascending)) {
    std::vector<std::uint32_t> held, merged;
    for (const std::vector<std::uint32_t>* list : lists) {
      merged.clear();
      std::set_union(held.begin(), held.end(), list->begin(), list->end(), std::back_inserter(merged));
      held.swap(merged);
    }
    held.erase(std::unique(held.begin(), held.end()), held.end());  // a list may name an object twice
    return held;
  }
  std::vector<char> isNamed(sceneObjects, 0);
  for (const std::vector<std::uint32_t>* list : lists)
    for (std::uint32_t g : *list) isNamed[g] = 1;
  std::vector<std::uint32_t> held;
  for (std::uint32_t g = 0; g < isNamed.size(); ++g)
    if (isNamed[g]) held.push_back(g);
  return held;
}

RegionDatabase regionDatabaseOf(const core::Scene& scene, std::vector<std::uint32_t> held) {
  RegionDatabase db;
  db.scene = withoutObjects(scene);
  db.scene.objects.reserve(held.size());
  for (std::uint32_t g : held) db.scene.objects.push_back(scene.objects[g]);
  db.globalIds = std::move(held);
  return db;
}

RegionDatabase regionDatabaseIn(const core::Scene& scene, const core::SceneFeatures& features,
                                std::vector<std::uint32_t> held) {
  RegionDatabase db;
  db.inPlace = &scene;
  db.inPlaceFeatures = features;
  db.globalIds = std::move(held);
  return db;
}

std::vector<std::uint32_t> RegionDatabase::heldIndices() const {
  return inPlace ? globalIds : core::everyObjectOf(scene);
}

void toLocalIndices(const RegionDatabase& database, ObjectLists lists) {
  const std::vector<std::uint32_t>& ids = database.globalIds;
  if (database.inPlace || ids.empty() || ids.back() + 1 == ids.size())
    return;  // every object up to the last: local is global
  std::vector<std::uint32_t> localOf(ids.back() + 1);
  for (std::uint32_t local = 0; local < ids.size(); ++local) localOf[ids[local]] = local;
  for (std::vector<std::uint32_t>* list : lists)
    for (std::uint32_t& o : *list) o = localOf[o];
}

RegionDatabase gatherRegionDatabase(const core::Scene& scene, ObjectLists lists) {
  RegionDatabase db = regionDatabaseOf(scene, heldObjectsOf(lists, scene.objects.size()));
  toLocalIndices(db, lists);
  return db;
}

std::vector<EyeBox> eyeBoxesOf(const std::vector<EyeBox>& eyeBoxes,
                               const std::vector<std::uint32_t>& objects) {
  std::vector<EyeBox> out;
  out.reserve(objects.size());
  for (std::uint32_t o : objects) out.push_back(eyeBoxes[o]);
  return out;
}

}  // namespace raycube::node
