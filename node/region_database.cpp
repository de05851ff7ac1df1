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

RegionDatabase gatherRegionDatabase(const core::Scene& scene, const std::vector<EyeBox>& eyeBoxes,
                                    std::span<std::vector<std::uint32_t>* const> lists) {
  RegionDatabase db;
  for (const std::vector<std::uint32_t>* list : lists)
    db.globalIds.insert(db.globalIds.end(), list->begin(), list->end());
  std::sort(db.globalIds.begin(), db.globalIds.end());
  db.globalIds.erase(std::unique(db.globalIds.begin(), db.globalIds.end()), db.globalIds.end());
  db.scene = withoutObjects(scene);
  db.scene.objects.reserve(db.globalIds.size());
  db.eyeBoxes.reserve(db.globalIds.size());
  for (std::uint32_t g : db.globalIds) {
    db.scene.objects.push_back(scene.objects[g]);
    db.eyeBoxes.push_back(eyeBoxes[g]);
  }
  auto localOf = [&](std::uint32_t g) {
    return std::uint32_t(std::lower_bound(db.globalIds.begin(), db.globalIds.end(), g) - db.globalIds.begin());
  };
  for (std::vector<std::uint32_t>* list : lists)
    for (std::uint32_t& o : *list) o = localOf(o);
  return db;
}

}  // namespace raycube::node
