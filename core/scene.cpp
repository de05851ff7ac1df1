#include "core/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/overloaded.h"

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

namespace {

double largest(const Vec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}
double largest(const std::vector<Vec3>& points) {
  double m = 0;
  for (const Vec3& p : points) m = std::max(m, largest(p));
  return m;
}

}  // namespace

double Scene::largestCoordinate() const {
  double m = std::max({largest(camera.from), largest(camera.at), std::abs(camera.hither)});
  for (const Light& light : lights) m = std::max(m, largest(light.position));
  for (const Object& object : objects)
    m = std::max(m,
                 std::visit(Overloaded{[](const Sphere& s) { return largest(s.center) + std::abs(s.radius); },
                                       [](const Cone& c) {
                                         return std::max(largest(c.base) + std::abs(c.baseRadius),
                                                         largest(c.apex) + std::abs(c.apexRadius));
                                       },
                                       [](const Polygon& p) { return largest(p.vertices); },
                                       [](const Patch& p) { return largest(p.vertices); }},
                            object.shape));
  return m;
}

void requireRepresentable(const Scene& scene, Precision precision) {
  const double limit = withPrecision(precision, []<class Real>() { return kLargestCoordinateOf<Real>; });
  const double largestCoordinate = scene.largestCoordinate();
  if (!(largestCoordinate <= limit))
    throw std::invalid_argument(fmt::format(
        "{}: a coordinate of magnitude {:g} is too large for --precision {} (at most {:g}, so that squared "
        "distances stay finite){}",
        scene.name.empty() ? "scene" : scene.name, largestCoordinate, nameOf(precision), limit,
        precision == Precision::Float ? "; use --precision double" : ""));
}

}  // namespace raycube::core
