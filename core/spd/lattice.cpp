// SPD lattice.c (Antonio Costa): shiny spheres on a cubic lattice, each joined to its neighbours by matte
// cylinders. Six lights. Every object is preceded by its own material line, as lattice.c prints them.
#include <fmt/format.h>

#include <cmath>

#include "core/spd/generators.h"
#include "core/spd/output.h"

namespace raycube::core {

namespace {

constexpr double kSphereRadius = 1.0 / 4.0;     // RADIUS1, over the size
constexpr double kCylinderRadius = 1.0 / 16.0;  // RADIUS2, over the size

struct Lattice {
  SpdOutput& out;
  int size;
  double step;    // 1 / size: the lattice spacing
  double inset;   // how far inside each sphere a cylinder starts
  double radius;  // of the cylinders

  // The cylinder from lattice point p to its neighbour along axis 0, 1 or 2, in that axis's colour.
  void cylinder(const Color& color, const Vec3& p, int axis) const {
    out.color(color, 0.99, 0.0, 0.0, 0.0, 0.0);
    Vec3 base = p;
    Vec3 end = p;
    base[axis] = p[axis] + inset;
    end[axis] = p[axis] + step - inset;
    out.cylcone(base, radius, end, radius);
  }

  void point(int x, int y, int z) const {
    const Vec3 p(double(x) / double(size), double(y) / double(size), double(z) / double(size));
    out.color(Color(0.9, 0.9, 0.9), 0.5, 0.5, 37.0, 0.0, 0.0);
    out.sphere(p, kSphereRadius / double(size));
    if (x != size) cylinder(Color(0.9, 0.1, 0.1), p, 0);
    if (y != size) cylinder(Color(0.1, 0.9, 0.1), p, 1);
    if (z != size) cylinder(Color(0.1, 0.1, 0.9), p, 2);
  }
};

}  // namespace

Scene makeLattice(int size) {
  requireSpdSize("lattice", size, kMaxLatticeSize,
                 "cells along an edge: 1 gives 20 primitives, 12 gives 8281");
  SpdOutput out(fmt::format("lattice{}", size));
  const double step = 1.0 / double(size);
  const double sphereRadius = kSphereRadius / double(size);
  const double inset = (sphereRadius * (1.0 - std::sqrt(kCylinderRadius / kSphereRadius))) * 0.99;

  out.background(Color(0.078, 0.361, 0.753));
  const double middle = (double(size >> 1) + 0.5) * step;
  const double lift = 1.0 / double(size << 1);
  out.viewpoint(Vec3(middle, 1.0, 1.0 - lift), Vec3(middle, -1.0, -1.0 - lift), Vec3(0.2, 1.0, 0.0), 60.0,
                0.0, 512, 512);
  for (const Vec3& light : {Vec3(2.0, 0.5, 0.5), Vec3(-1.0, 0.5, 0.5), Vec3(0.5, 2.0, 0.5),
                            Vec3(0.5, -1.0, 0.5), Vec3(0.5, 0.5, 2.0), Vec3(0.5, 0.5, -1.0)}) {
    out.light(light);
  }

  const std::size_t points = std::size_t(size + 1) * (size + 1) * (size + 1);
  out.reserve(points + 3 * std::size_t(size) * (size + 1) * (size + 1));
  const Lattice lattice{out, size, step, inset, kCylinderRadius / double(size)};
  for (int x = 0; x <= size; ++x) {
    for (int y = 0; y <= size; ++y) {
      for (int z = 0; z <= size; ++z) lattice.point(x, y, z);
    }
  }
  return std::move(out).finish();
}

}  // namespace raycube::core
