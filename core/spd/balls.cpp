#include "core/spd/balls.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/spd/matrix.h"

namespace raycube::core {

namespace {

// balls.c create_objset(): the 9 unit directions of the children around a parent whose axis is +Z, three
// trios rotated 120 degrees apart.
std::array<Vec3, 9> childDirections() {
  const double dist = 1.0 / std::sqrt(2.0);
  std::array<Vec3, 3> trio{Vec3(dist, dist, 0.0), Vec3(dist, 0.0, -dist), Vec3(0.0, dist, -dist)};
  const SpdMatrix tilt =
      spdAxisRotation(glm::normalize(Vec3(1.0, -1.0, 0.0)), std::asin(2.0 / std::sqrt(6.0)));
  for (Vec3& direction : trio) direction = spdTransformVector(direction, tilt);
  std::array<Vec3, 9> directions;
  for (int set = 0; set < 3; ++set) {
    const SpdMatrix spin = spdRotation(SpdAxis::Z, set * 2.0 * std::numbers::pi / 3.0);
    for (int vertex = 0; vertex < 3; ++vertex)
      directions[set * 3 + vertex] = spdTransformVector(trio[vertex], spin);
  }
  return directions;
}

// balls.c output_object(): the parent sphere, then each child's subtree, depth first.
void addFlake(Scene& scene, const std::array<Vec3, 9>& directions, int depth, const Vec3& center,
              double radius, const Vec3& axis) {
  constexpr double kChildRatio = 1.0 / 3.0;  // a child's radius over its parent's
  scene.objects.push_back(Object{Sphere{center, radius}, 1, false});
  if (depth <= 0) return;
  SpdMatrix orient;
  if (axis.z >= 1.0) {
    orient = spdIdentity();
  } else if (axis.z <= -1.0) {
    orient = spdRotation(SpdAxis::Y, std::numbers::pi);
  } else {
    // lib_normalize_vector leaves a zero vector as it is: an axis a rounding step off +Z (from size 5 on)
    // has no rotation axis, and the matrix is then the identity scaled by cos(angle), not NaN.
    const Vec3 across = glm::cross(Vec3(0, 0, 1), axis);
    orient =
        spdAxisRotation(glm::dot(across, across) > 0 ? glm::normalize(across) : across, std::acos(axis.z));
  }
  const double scale = radius * (1.0 + kChildRatio);
  for (const Vec3& direction : directions) {
    const Vec3 child = spdTransformVector(direction, orient) * scale + center;
    addFlake(scene, directions, depth - 1, child, radius * kChildRatio, (child - center) / scale);
  }
}

}  // namespace

Scene makeBalls(int size) {
  if (size < 1 || size > kMaxBallsSize) {
    throw std::invalid_argument(
        fmt::format("balls size must be from 1 to {} (the sphereflake's recursion depth: 1 gives 10 spheres, "
                    "{} gives 597871), "
                    "got {}",
                    kMaxBallsSize, kMaxBallsSize, size));
  }
  Scene scene;
  scene.name = fmt::format("balls{}", size);
  scene.background = Color(0.078, 0.361, 0.753);  // UNC sky blue
  scene.camera.from = Vec3(2.1, 1.3, 1.7);
  scene.camera.at = Vec3(0, 0, 0);
  scene.camera.up = Vec3(0, 0, 1);
  scene.camera.angleDegrees = 45;
  scene.camera.hither = 0.01;
  scene.camera.width = 512;
  scene.camera.height = 512;
  for (const Vec3& position : {Vec3(4, 3, 2), Vec3(1, -4, 4), Vec3(-3, 1, 5)}) {
    scene.lights.push_back(Light{position, Color(1, 1, 1), false});
  }
  // The two "f" lines balls.c prints in NFF (its lib turns a 37-degree highlight into Shine 3.0827; a zero
  // highlight angle into 100000).
  scene.materials.push_back(Material{Color(1, 0.75, 0.33), 0.8, 0, 100000, 0, 1});  // beige floor
  scene.materials.push_back(Material{Color(1, 0.9, 0.7), 0.5, 0.5, 3.0827, 0, 1});  // mirrored balls

  constexpr double kRadius = 1.0;  // of the sphere enclosing the whole flake
  const double floorZ = -kRadius / 2.0;
  scene.objects.push_back(
      Object{Polygon{{Vec3(12 * kRadius, 12 * kRadius, floorZ), Vec3(-12 * kRadius, 12 * kRadius, floorZ),
                      Vec3(-12 * kRadius, -12 * kRadius, floorZ), Vec3(12 * kRadius, -12 * kRadius, floorZ)}},
             0, false});
  std::size_t spheres = 0;
  for (int level = 0, count = 1; level <= size; ++level, count *= 9) spheres += count;
  scene.objects.reserve(1 + spheres);
  addFlake(scene, childDirections(), size, Vec3(0, 0, 0), kRadius / 2.0, Vec3(0, 0, 1));
  return scene;
}

}  // namespace raycube::core
