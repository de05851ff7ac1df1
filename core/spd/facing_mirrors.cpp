#include "core/spd/facing_mirrors.h"

#include <fmt/format.h>

#include <stdexcept>

namespace raycube::core {

Scene makeFacingMirrors(double ks) {
  if (!(ks >= 0 && ks <= 1)) {
    throw std::invalid_argument(
        fmt::format("facing mirrors: ks must be from 0 to 1 (the mirrors' reflectance), got {}", ks));
  }
  Scene scene;
  scene.name = "facing_mirrors";
  scene.background = Color(0, 0, 0);
  // The steepest eye ray (corner of the 20-degree view, tilted 5.7 degrees) drifts sideways 0.334 per unit
  // of z, so under 43 units over the 127 units of z of 64 hits: far inside the 100 half-side.
  scene.camera.from = Vec3(0, 0, 0);
  scene.camera.at = Vec3(0.1, 0, -1);
  scene.camera.up = Vec3(0, 1, 0);
  scene.camera.angleDegrees = 20;
  scene.camera.hither = 0.01;
  scene.camera.width = 64;
  scene.camera.height = 64;
  // Between the mirrors, so N.L > 0 at every hit: each bounce sends a light ray while its weight is not 0.
  scene.lights.push_back(Light{Vec3(0, 0, 0.5), Color(1, 1, 1), false});
  scene.materials.push_back(Material{Color(1, 1, 1), 0.1, ks, 10, 0, 1});

  constexpr double kHalfSide = 100;
  constexpr double kHalfGap = 1;
  // Counter-clockwise seen from between the mirrors: both normals face the gap.
  scene.objects.push_back(
      Object{Polygon{{Vec3(-kHalfSide, -kHalfSide, -kHalfGap), Vec3(kHalfSide, -kHalfSide, -kHalfGap),
                      Vec3(kHalfSide, kHalfSide, -kHalfGap), Vec3(-kHalfSide, kHalfSide, -kHalfGap)}},
             0, false});
  scene.objects.push_back(
      Object{Polygon{{Vec3(-kHalfSide, -kHalfSide, kHalfGap), Vec3(-kHalfSide, kHalfSide, kHalfGap),
                      Vec3(kHalfSide, kHalfSide, kHalfGap), Vec3(kHalfSide, -kHalfSide, kHalfGap)}},
             0, false});
  return scene;
}

}  // namespace raycube::core
