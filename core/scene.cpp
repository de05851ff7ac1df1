#include "core/scene.h"

namespace raycube::core {

SceneFeatures Scene::features() const {
  SceneFeatures f;
  f.lightCount = lights.size();
  for (const Object& object : objects) {
    const Material& m = materials.at(object.material);
    f.transmission |= m.transmittance > 0;
    f.reflection |= m.ks > 0;
    f.spheres |= std::holds_alternative<Sphere>(object.shape);
    f.cones |= std::holds_alternative<Cone>(object.shape);
    f.polygons |= std::holds_alternative<Polygon>(object.shape);
    f.patches |= std::holds_alternative<Patch>(object.shape);
  }
  return f;
}

}  // namespace raycube::core
