#include "node/region_database.h"

#include <cstdint>

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
  constexpr std::uint32_t kNotHeld = UINT32_MAX;
  std::vector<std::uint32_t> localOf(scene.objects.size(), kNotHeld);
  for (const std::vector<std::uint32_t>* list : lists)
    for (std::uint32_t g : *list) localOf[g] = 0;
  RegionDatabase db;
  db.scene = withoutObjects(scene);
  for (std::uint32_t g = 0; g < localOf.size(); ++g) {
    if (localOf[g] == kNotHeld) continue;
    localOf[g] = std::uint32_t(db.globalIds.size());
    db.globalIds.push_back(g);
    db.scene.objects.push_back(scene.objects[g]);
    db.eyeBoxes.push_back(eyeBoxes[g]);
  }
  for (std::vector<std::uint32_t>* list : lists)
    for (std::uint32_t& o : *list) o = localOf[o];
  return db;
}

}  // namespace raycube::node
