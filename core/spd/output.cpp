#include "core/spd/output.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <utility>

namespace raycube::core {

namespace {

// def.h's EPSILON2 outside the Macintosh build: shorter polygon edges than this are collapsed.
constexpr double kSpdEdgeEpsilon = 1.0e-6;

// lib_output_color's conversion of a highlight half angle (degrees) to a Phong exponent.
double phongPower(double highlightDegrees) {
  const double radians = std::numbers::pi * highlightDegrees / 180.0;
  if (radians <= 0.0) return 100000.0;  // "essentially invisible, very very sharp"
  if (radians >= std::numbers::pi / 2.0) return 1.0;
  return std::log(0.5) / std::log(std::cos(radians));
}

std::vector<Vec3> withoutDegenerateEdges(std::vector<Vec3> vertices) {
  for (std::size_t i = 0; i < vertices.size();) {
    const Vec3 edge = vertices[i] - vertices[(i + 1) % vertices.size()];
    if (std::sqrt(edge.x * edge.x + edge.y * edge.y + edge.z * edge.z) < kSpdEdgeEpsilon) {
      vertices.erase(vertices.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      ++i;
    }
  }
  return vertices;
}

}  // namespace

double spdPrinted(double x) {
  // to_chars with general format and precision 6 is printf's "%g" (C++20 [charconv.to.chars]), and faster.
  char text[32];
  const auto printed = std::to_chars(text, text + sizeof text, x, std::chars_format::general, 6);
  double value = 0;
  std::from_chars(text, printed.ptr, value);
  return value;
}

Vec3 spdPrinted(const Vec3& v) {
  return Vec3(spdPrinted(v.x), spdPrinted(v.y), spdPrinted(v.z));
}

SpdOutput::SpdOutput(std::string sceneName) {
  scene_.name = std::move(sceneName);
}

void SpdOutput::background(const Color& color) {
  scene_.background = spdPrinted(color);
}

void SpdOutput::viewpoint(const Vec3& from, const Vec3& at, const Vec3& up, double angleDegrees,
                          double hither, int width, int height) {
  Camera& camera = scene_.camera;
  camera.from = spdPrinted(from);
  camera.at = spdPrinted(at);
  camera.up = spdPrinted(up);
  camera.angleDegrees = spdPrinted(angleDegrees);
  camera.hither = spdPrinted(hither);
  camera.width = width;
  camera.height = height;
}

void SpdOutput::light(const Vec3& position) {
  scene_.lights.push_back(Light{spdPrinted(position), Color(1, 1, 1), false});
}

void SpdOutput::color(const Color& color, double kd, double ks, double highlightDegrees, double kt,
                      double ior) {
  scene_.materials.push_back(Material{spdPrinted(color), spdPrinted(kd), spdPrinted(ks),
                                      spdPrinted(phongPower(highlightDegrees)), spdPrinted(kt),
                                      spdPrinted(ior)});
}

void SpdOutput::sphere(const Vec3& center, double radius) {
  add(Sphere{spdPrinted(center), spdPrinted(radius)});
}

void SpdOutput::cylcone(const Vec3& base, double baseRadius, const Vec3& apex, double apexRadius) {
  add(Cone{spdPrinted(base), spdPrinted(baseRadius), spdPrinted(apex), spdPrinted(apexRadius)});
}

void SpdOutput::polygon(std::vector<Vec3> vertices) {
  vertices = withoutDegenerateEdges(std::move(vertices));
  if (vertices.size() < 3) return;
  for (Vec3& vertex : vertices) vertex = spdPrinted(vertex);
  add(Polygon(std::move(vertices)));
}

void SpdOutput::add(Shape shape) {
  scene_.objects.push_back(
      Object{std::move(shape), static_cast<std::uint32_t>(scene_.materials.size() - 1), false});
}

}  // namespace raycube::core
