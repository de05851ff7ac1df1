#include "core/nff_writer.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <sstream>

namespace raycube::core {

namespace {

// fmt's "{}" is the shortest round-trip representation of a double.
std::string numbers(const Vec3& v) {
  return fmt::format("{} {} {}", v.x, v.y, v.z);
}

void writeView(std::ostream& out, const Camera& camera) {
  fmt::print(out, "v\nfrom {}\nat {}\nup {}\nangle {}\nhither {}\nresolution {} {}\n", numbers(camera.from),
             numbers(camera.at), numbers(camera.up), camera.angleDegrees, camera.hither, camera.width,
             camera.height);
}

void writeLight(std::ostream& out, const Light& light) {
  if (light.hasColor) {
    fmt::print(out, "l {} {}\n", numbers(light.position), numbers(light.color));
  } else {
    fmt::print(out, "l {}\n", numbers(light.position));
  }
}

void writeMaterial(std::ostream& out, const Material& m) {
  fmt::print(out, "f {} {} {} {} {} {}\n", numbers(m.color), m.kd, m.ks, m.shine, m.transmission, m.ior);
}

// NFF marks an inside-visible sphere or cone by negative radii.
double signedRadius(double radius, bool insideVisible) {
  return insideVisible ? -radius : radius;
}

void writeShape(std::ostream& out, const Object& object) {
  const Shape& shape = object.shape;
  if (const auto* sphere = std::get_if<Sphere>(&shape)) {
    fmt::print(out, "s {} {}\n", numbers(sphere->center), signedRadius(sphere->radius, object.insideVisible));
  } else if (const auto* cone = std::get_if<Cone>(&shape)) {
    fmt::print(out, "c {} {} {} {}\n", numbers(cone->base),
               signedRadius(cone->baseRadius, object.insideVisible), numbers(cone->apex),
               signedRadius(cone->apexRadius, object.insideVisible));
  } else if (const auto* polygon = std::get_if<Polygon>(&shape)) {
    fmt::print(out, "p {}\n", polygon->vertices.size());
    for (const Vec3& vertex : polygon->vertices) fmt::print(out, "{}\n", numbers(vertex));
  } else {
    const auto& patch = std::get<Patch>(shape);
    fmt::print(out, "pp {}\n", patch.vertices.size());
    for (std::size_t i = 0; i < patch.vertices.size(); ++i) {
      fmt::print(out, "{} {}\n", numbers(patch.vertices[i]), numbers(patch.normals[i]));
    }
  }
}

}  // namespace

void writeNff(std::ostream& out, const Scene& scene, const std::string& comment) {
  if (!comment.empty()) fmt::print(out, "# {}\n", comment);
  fmt::print(out, "b {}\n", numbers(scene.background));
  writeView(out, scene.camera);
  for (const Light& light : scene.lights) writeLight(out, light);
  std::size_t printed = 0;  // materials printed so far, in index order
  std::size_t current = scene.materials.size();
  for (const Object& object : scene.objects) {
    if (object.material >= printed) {
      for (; printed <= object.material; ++printed) writeMaterial(out, scene.materials[printed]);
    } else if (object.material != current) {
      writeMaterial(out, scene.materials[object.material]);
    }
    current = object.material;
    writeShape(out, object);
  }
  for (; printed < scene.materials.size(); ++printed) writeMaterial(out, scene.materials[printed]);
}

std::string nffText(const Scene& scene, const std::string& comment) {
  std::ostringstream text;
  writeNff(text, scene, comment);
  return text.str();
}

}  // namespace raycube::core
