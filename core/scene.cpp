#include "core/scene.h"

#include <algorithm>
#include <cmath>

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

Scene scaledBy(Scene scene, double factor) {
  scene.camera.from *= factor;
  scene.camera.at *= factor;
  scene.camera.hither *= factor;
  for (Light& light : scene.lights) light.position *= factor;
  for (Object& object : scene.objects)
    std::visit(Overloaded{[&](Sphere& s) {
                            s.center *= factor;
                            s.radius *= factor;
                          },
                          [&](Cone& c) {
                            c.base *= factor;
                            c.apex *= factor;
                            c.baseRadius *= factor;
                            c.apexRadius *= factor;
                          },
                          [&](Polygon& p) {
                            for (Vec3& v : p.vertices) v *= factor;
                          },
                          [&](Patch& p) {  // vertices only, never the normals
                            for (Vec3& v : p.vertices) v *= factor;
                          }},
               object.shape);
  return scene;
}

std::optional<Scene> rescaledFor(const Scene& scene, Precision precision) {
  const int safe = withPrecision(precision, []<class Real>() { return kSafeExponentOf<Real>; });
  const double largestCoordinate = scene.largestCoordinate();
  if (!(largestCoordinate > 0) || !std::isfinite(largestCoordinate)) return std::nullopt;
  const int exponent = std::ilogb(largestCoordinate);
  if (exponent >= -safe && exponent <= safe) return std::nullopt;
  return scaledBy(scene, std::ldexp(1.0, -exponent));
}

}  // namespace raycube::core
