// SPD tetra.c (Eric Haines): a recursive tetrahedral pyramid (Sierpinski's tetrahedron), after the scene
// of Glassner and of Kay & Kajiya, with their view and light. One light, no reflection.
#include <fmt/format.h>

#include <array>
#include <utility>

#include "core/spd/generators.h"
#include "core/spd/output.h"

namespace raycube::core {

namespace {

// The corners (x, y, z) in {-1, 1}^3 with x*y*z == 1, in tetra.c's loop order: the tetrahedron inscribed in
// the cube of half side 1.
std::array<Vec3, 4> tetrahedronCorners() {
  std::array<Vec3, 4> corners;
  int n = 0;
  for (int x = -1; x <= 1; x += 2) {
    for (int y = -1; y <= 1; y += 2) {
      for (int z = -1; z <= 1; z += 2) {
        if (x * y * z == 1) corners[n++] = Vec3(x, y, z);
      }
    }
  }
  return corners;
}

// tetra.c's face order: 0 1 2, 3 2 1, 2 3 0, 1 0 3.
void outputTetrahedron(SpdOutput& out, const Vec3& center, double halfSide) {
  std::array<Vec3, 4> points;
  const std::array<Vec3, 4> corners = tetrahedronCorners();
  for (int i = 0; i < 4; ++i) {
    points[i] = Vec3(center.x + corners[i].x * halfSide, center.y + corners[i].y * halfSide,
                     center.z + corners[i].z * halfSide);
  }
  for (int face = 0; face < 4; ++face) {
    std::array<int, 3> order{face % 4, (face + 1) % 4, (face + 2) % 4};
    if (face % 2 == 1) std::swap(order[0], order[2]);
    out.polygon({points[order[0]], points[order[1]], points[order[2]]});
  }
}

// tetra.c create_tetra(): four half-size tetrahedra at alternate corners of the cube, down to depth 1.
void createTetra(SpdOutput& out, int depth, const Vec3& center, double halfSide) {
  if (depth <= 1) {
    outputTetrahedron(out, center, halfSide);
    return;
  }
  for (const Vec3& corner : tetrahedronCorners()) {
    createTetra(out, depth - 1,
                Vec3(center.x + corner.x * halfSide / 2.0, center.y + corner.y * halfSide / 2.0,
                     center.z + corner.z * halfSide / 2.0),
                halfSide / 2.0);
  }
}

}  // namespace

Scene makeTetra(int size) {
  requireSpdSize("tetra", size, kMaxTetraSize, "the recursion depth: 1 gives 4 triangles, 6 gives 4096");
  SpdOutput out(fmt::format("tetra{}", size));
  out.background(Color(0.078, 0.361, 0.753));
  out.viewpoint(Vec3(1.022846, -3.177154, -2.174512), Vec3(-0.004103, -0.004103, 0.216539),
                Vec3(-0.816497, -0.816497, 0.816497), 45.0, 1.0, 512, 512);
  out.light(Vec3(2.0, -18.0, -5.0));
  out.color(Color(1.0, 0.2, 0.2), 1.0, 0.0, 0.0, 0.0, 0.0);
  out.reserve(std::size_t(1) << (2 * size));
  createTetra(out, size, Vec3(0, 0, 0), 1.0);
  return std::move(out).finish();
}

}  // namespace raycube::core
