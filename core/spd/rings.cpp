// SPD rings.c (Eric Haines): objects of six pentagonal rings, which join the midpoints of a dodecahedron's
// edges, stacked in a pyramid that the viewer looks at from its tip, before a white wall. Three lights.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>

#include "core/spd/generators.h"
#include "core/spd/matrix.h"
#include "core/spd/output.h"

namespace raycube::core {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRadius = 0.07412;  // of the ring's cylinders and spheres
constexpr int kRingPoints = 30;      // 6 pentagons

// rings.c create_dodec(): the 30 ring vertices, a pentagon on the XY plane and five copies tilted by the
// dodecahedron's dihedral angle, scaled to fit with the tubes in a unit sphere.
std::array<Vec3, kRingPoints> ringPoints() {
  std::array<Vec3, kRingPoints> points;
  const double scale = 1.0 / (1.0 + kRadius);
  for (int v = 0; v < 5; ++v) {
    points[v] = Vec3(scale * std::cos(double(v) * 2.0 * kPi / 5.0),
                     scale * std::sin(double(v) * 2.0 * kPi / 5.0), 0.0);
  }
  const double dihedral = 2.0 * std::acos(std::cos(kPi / 3.0) / std::sin(kPi / 5.0));
  const SpdMatrix tilt = spdRotation(SpdAxis::X, dihedral);
  for (int pentagon = 1; pentagon < 6; ++pentagon) {
    const SpdMatrix turn = spdRotation(SpdAxis::Z, kPi * (2.0 * double(pentagon - 1) + 1.0) / 5.0);
    for (int v = 0; v < 5; ++v) {
      points[5 * pentagon + v] = spdTransformPoint(spdTransformPoint(points[v], tilt), turn);
    }
  }
  return points;
}

// One rings object at `offset`: per ring a material, then per point the tube to the previous point of its
// pentagon and the sphere on the point.
void outputRings(SpdOutput& out, const std::array<Vec3, kRingPoints>& points, const Vec3& offset) {
  static const std::array<Color, 6> kRingColors{Color(1, 0, 0), Color(0, 1, 0), Color(0, 0, 1),
                                                Color(0, 1, 1), Color(1, 0, 1), Color(1, 1, 0)};
  for (int point = 0; point < kRingPoints; ++point) {
    int previous = point - 1;
    if (point % 5 == 0) {
      previous = point + 4;
      out.color(kRingColors[point / 5], 0.5, 0.2, 37.0, 0.0, 0.0);
    }
    const Vec3 base = points[point] + offset;
    out.cylcone(base, kRadius, points[previous] + offset, kRadius);
    out.sphere(base, kRadius);
  }
}

}  // namespace

Scene makeRings(int size) {
  requireSpdSize("rings", size, kMaxRingsSize, "the pyramid's layers: 1 gives 61 primitives, 7 gives 8401");
  SpdOutput out(fmt::format("rings{}", size));
  const double spread = 1 / std::sin(kPi / 8.0);  // SPREAD_OUT is 1: layers spaced along y only
  const double yDiff = spread;
  const double xzDiff = 1.0;
  out.background(Color(0.078, 0.361, 0.753));
  const Vec3 from(-1.0, -spread, 0.5);
  out.viewpoint(from, Vec3(from.x, from.y + 1.0, from.z), Vec3(0, 0, 1), 45.0, 1.0, 512, 512);
  for (const Vec3& light : {Vec3(3.0, -spread, 3.0), Vec3(-4.0, -spread, 1.0), Vec3(2.0, -spread, -4.0)}) {
    out.light(light);
  }

  out.color(Color(1, 1, 1), 1.0, 0.0, 0.0, 0.0, 0.0);
  // The wall just spans the 45 degree view, plus 1%.
  const double wallY = yDiff * (size + 1);
  const double wallXZ = 1.01 * (wallY - from.y) * std::tan(kPi / 8.0);
  out.polygon({Vec3(wallXZ + from.x, wallY, wallXZ + from.z), Vec3(-wallXZ + from.x, wallY, wallXZ + from.z),
               Vec3(-wallXZ + from.x, wallY, -wallXZ + from.z),
               Vec3(wallXZ + from.x, wallY, -wallXZ + from.z)});

  out.reserve(1 + std::size_t(10) * size * (size + 1) * (2 * size + 1));
  const std::array<Vec3, kRingPoints> points = ringPoints();
  for (int depth = 0; depth < size; ++depth) {
    for (int row = 0; row <= depth; ++row) {
      for (int column = 0; column <= depth; ++column) {
        outputRings(out, points,
                    Vec3(xzDiff * double(2 * column - depth), yDiff * double(depth + 1),
                         xzDiff * double(2 * row - depth)));
      }
    }
  }
  return std::move(out).finish();
}

}  // namespace raycube::core
