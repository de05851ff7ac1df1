#pragma once
// Shared by the scale tests: the same scene at another size.
#include <type_traits>
#include <variant>

#include "core/scene.h"

namespace raycube::testing_support {

// Every length of the scene times `factor`: camera position, target and hither, lights, and all geometry.
// Directions (up, patch normals), angles, colours and materials are unit-free and stay.
inline core::Scene scaled(core::Scene scene, double factor) {
  scene.camera.from *= factor;
  scene.camera.at *= factor;
  scene.camera.hither *= factor;
  for (core::Light& light : scene.lights) light.position *= factor;
  for (core::Object& object : scene.objects) {
    std::visit(
        [&](auto& shape) {
          using T = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<T, core::Sphere>) {
            shape.center *= factor;
            shape.radius *= factor;
          } else if constexpr (std::is_same_v<T, core::Cone>) {
            shape.base *= factor;
            shape.apex *= factor;
            shape.baseRadius *= factor;
            shape.apexRadius *= factor;
          } else {  // Polygon, Patch: vertices only, never the normals
            for (core::Vec3& v : shape.vertices) v *= factor;
          }
        },
        object.shape);
  }
  return scene;
}

}  // namespace raycube::testing_support
