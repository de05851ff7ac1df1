#include "core/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <utility>

#include "core/overloaded.h"
#include "core/polygon_outline.h"
#include "core/ray.h"

namespace raycube::core {

Polygon::Polygon(std::vector<Vec3> points)
    : outline(points.size() > kMostFanVertices ? std::make_shared<const PolygonOutline>(points) : nullptr) {
  vertices = Corners(std::move(points));
}

double spdIntensity(std::size_t lights) {
  if (lights == 0) return 0.5;
  const double count = double(lights);
  return std::sqrt(count) / (2 * count);
}

SceneFeatures Scene::features() const {
  SceneFeatures f;
  f.lightCount = lights.size();
  for (const Object& object : objects) {
    const Material& m = materials.at(object.material);
    f.transmission |= m.transmission > 0;
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
double largest(std::span<const Vec3> points) {
  double m = 0;
  for (const Vec3& p : points) m = std::max(m, largest(p));
  return m;
}

double largestCoordinateOf(const Object& object) {
  return std::visit(Overloaded{[](const Sphere& s) { return largest(s.center) + std::abs(s.radius); },
                               [](const Cone& c) {
                                 return std::max(largest(c.base) + std::abs(c.baseRadius),
                                                 largest(c.apex) + std::abs(c.apexRadius));
                               },
                               [](const Polygon& p) { return largest(p.vertices); },
                               [](const Patch& p) { return largest(p.vertices); }},
                    object.shape);
}

// Largest side of the object's bounding box: its scale.
double sizeOf(const Object& object) {
  const auto sideOf = [](std::span<const Vec3> points) {
    Vec3 lo = points.front(), hi = points.front();
    for (const Vec3& p : points) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    return largest(hi - lo);
  };
  return std::visit(Overloaded{[](const Sphere& s) { return 2 * std::abs(s.radius); },
                               [&](const Cone& c) {
                                 return std::max({largest(c.apex - c.base), 2 * std::abs(c.baseRadius),
                                                  2 * std::abs(c.apexRadius)});
                               },
                               [&](const Polygon& p) { return sideOf(p.vertices); },
                               [&](const Patch& p) { return sideOf(p.vertices); }},
                    object.shape);
}

const char* keywordOf(const Object& object) {
  return std::visit(
      Overloaded{[](const Sphere&) { return "sphere 's'"; }, [](const Cone&) { return "cone 'c'"; },
                 [](const Polygon&) { return "polygon 'p'"; }, [](const Patch&) { return "patch 'pp'"; }},
      object.shape);
}

// "scene.nff:12: the sphere 's'" or "object 12 (sphere 's')" for scenes built in code.
std::string placeOf(const Scene& scene, int line, std::size_t index, const std::string& what) {
  if (line > 0 && !scene.source.empty()) return fmt::format("{}:{}: the {}", scene.source, line, what);
  return fmt::format("{} {}", what, index);
}

}  // namespace

double Scene::largestCoordinate() const {
  double m = std::max({largest(camera.from), largest(camera.at), std::abs(camera.hither)});
  for (const Light& light : lights) m = std::max(m, largest(light.position));
  for (const Object& object : objects) m = std::max(m, largestCoordinateOf(object));
  return m;
}

void requireRenderable(const Scene& scene, Precision precision) {
  if (scene.lights.size() > kMaxLights)
    throw std::invalid_argument(
        fmt::format("{}: {} lights; a ray names its light in 16 bits, so at most {} are supported",
                    scene.source.empty() ? scene.name : scene.source, scene.lights.size(), kMaxLights));
  if (scene.objects.empty()) return;
  // The element that sets the scale, and the smallest object, which the rescaling would crush.
  std::string farthest = placeOf(scene, scene.camera.line, 0, "camera ('v' block)");
  double largestCoordinate = std::max({largest(scene.camera.from), largest(scene.camera.at)});
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
    if (largest(scene.lights[i].position) > largestCoordinate) {
      largestCoordinate = largest(scene.lights[i].position);
      farthest = placeOf(scene, scene.lights[i].line, i, "light 'l'");
    }
  std::size_t smallest = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    if (largestCoordinateOf(object) > largestCoordinate) {
      largestCoordinate = largestCoordinateOf(object);
      farthest = placeOf(scene, object.line, i, keywordOf(object));
    }
    if (sizeOf(object) < sizeOf(scene.objects[smallest])) smallest = i;
  }
  const double span = largestCoordinate / sizeOf(scene.objects[smallest]);
  const auto spanExponent = [](Precision p) {
    return withPrecision(p, []<class Real>() { return kMaxSpanExponentOf<Real>; });
  };
  if (!(std::isfinite(span) && std::ilogb(span) <= spanExponent(precision))) {
    const bool doubleHolds = std::isfinite(span) && std::ilogb(span) <= spanExponent(Precision::Double);
    throw std::invalid_argument(fmt::format(
        "{} reaches {:.3g} from the origin, {:.3g} times the size of the smallest object ({}): {} arithmetic "
        "holds a ratio below 2^{}, beyond which every other object would vanish; {}",
        farthest, largestCoordinate, span,
        placeOf(scene, scene.objects[smallest].line, smallest, keywordOf(scene.objects[smallest])),
        nameOf(precision), spanExponent(precision) + 1,
        doubleHolds ? "render with --precision double" : "move or remove it"));
  }
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
                            std::vector<Vec3> vertices = p.vertices.toVector();
                            for (Vec3& v : vertices) v *= factor;
                            p = Polygon(std::move(vertices));
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
