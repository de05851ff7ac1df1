// SPD mount.c (Eric Haines): a fractal mountain by Carpenter's midpoint displacement on a square grid, with a
// pyramid of four glass spheres before it. One light. The mountain uses mount.c's original hash (the SPD's
// default, "for consistency with previously published results"), repetitions and all.
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/spd/generators.h"
#include "core/spd/matrix.h"
#include "core/spd/output.h"

namespace raycube::core {

namespace {

constexpr double kFractalDimension = 2.2;
constexpr long kMountainNumber = 21;  // MOUNTAIN_NO: another number, another mountain
constexpr double kCorner = -1.0;      // X_CORNER and Y_CORNER
constexpr double kWidth = 2.0;

// mount.c's hash_rand, the "old, buggy" one: the low 16 bits of three shifted copies of the grid indices.
long hashRand(int a, int b, int size) {
  const auto ua = static_cast<std::uint64_t>(static_cast<std::int64_t>(a));
  const auto ub = static_cast<std::uint64_t>(static_cast<std::int64_t>(b));
  return static_cast<long>(((ua << (23 - size)) + (ub << (15 - size)) + (ua << (7 - size))) & 0xffff);
}

// libvec.c lib_gauss_rand: a Gaussian deviate from Numerical Recipes' GASDEV, seeded by `seed`.
double gaussRand(long seed) {
  constexpr long kM = 134456;
  constexpr long kA = 8121;
  constexpr long kC = 28411;
  long x1 = 0;
  long x2 = seed;
  double v1 = 0;
  double r = 0;
  do {
    x1 = (kC + x2 * kA) % kM;
    x2 = (kC + x1 * kA) % kM;
    v1 = double(x1) * 2.0 * 1.0 / double(kM) - 1.0;  // RM1 is the macro 1.0/M1
    const double v2 = double(x2) * 2.0 * 1.0 / double(kM) - 1.0;
    r = v1 * v1 + v2 * v2;
  } while (r >= 1.0);
  return v1 * std::sqrt(-2.0 * std::log(r) / r);
}

// Heights at the corners of a grid square: lower left, lower right, upper right, upper left.
struct Corners {
  double ll, lr, ur, ul;
};

struct Mountain {
  SpdOutput& out;
  int size;
  double points;     // grid squares along a side, 2^size
  double roughness;  // scales each midpoint's random rise

  double displaced(int x, int y, double mean, double rise) const {
    return mean + rise * gaussRand(kMountainNumber + hashRand(x, y, size));
  }

  // mount.c grow_mountain(): split the square into four until it is one grid square, then print it as two
  // triangles.
  void grow(int width, int llX, int llY, const Corners& z) const {
    if (width == 1) {
      outputSquare(llX, llY, z);
      return;
    }
    const int half = width >> 1;
    const double rise = double(half) * kWidth / points * roughness;
    const double lower = displaced(llX + half, llY, (z.ll + z.lr) / 2.0, rise);
    const double right = displaced(llX + width, llY + half, (z.lr + z.ur) / 2.0, rise);
    const double upper = displaced(llX + half, llY + width, (z.ur + z.ul) / 2.0, rise);
    const double left = displaced(llX, llY + half, (z.ul + z.ll) / 2.0, rise);
    const double middle =
        displaced(llX + half, llY + half, (z.ll + z.lr + z.ur + z.ul) / 4.0, 1.4142136 * rise);
    grow(half, llX, llY, {z.ll, lower, middle, left});
    grow(half, llX + half, llY, {lower, z.lr, right, middle});
    grow(half, llX + half, llY + half, {middle, right, z.ur, upper});
    grow(half, llX, llY + half, {left, middle, upper, z.ul});
  }

  void outputSquare(int llX, int llY, const Corners& z) const {
    const double lx = kCorner + double(llX) * kWidth / points;
    const double rx = kCorner + double(llX + 1) * kWidth / points;
    const double ly = kCorner + double(llY) * kWidth / points;
    const double uy = kCorner + double(llY + 1) * kWidth / points;
    const Vec3 corners[4] = {Vec3(lx, ly, z.ll), Vec3(rx, ly, z.lr), Vec3(rx, uy, z.ur), Vec3(lx, uy, z.ul)};
    out.polygon({corners[0], corners[1], corners[2]});
    out.polygon({corners[2], corners[3], corners[0]});
  }
};

// mount.c create_spheres(): one sphere on top of three, touching.
void outputSpheres(SpdOutput& out, const Vec3& center, double radius) {
  const Vec3 axis = spdNormalized(Vec3(1.0, 1.0, 0.0));
  const Vec3 top(0.0, 0.0, radius * std::sqrt(3.0 / 2.0));
  out.sphere(center + top, radius);
  const Vec3 tilted = spdTransformVector(top, spdAxisRotation(axis, std::acos(-1.0 / 3.0)));
  for (int i = 0; i < 3; ++i) {
    const SpdMatrix turn = spdRotation(SpdAxis::Z, double(i) * 2.0 * std::numbers::pi / 3.0);
    out.sphere(spdTransformVector(tilted, turn) + center, radius);
  }
}

}  // namespace

Scene makeMount(int size) {
  requireSpdSize("mount", size, kMaxMountSize,
                 "the fractal's subdivisions: 1 gives 12 primitives, 6 gives 8196");
  SpdOutput out(fmt::format("mount{}", size));
  out.background(Color(0.078, 0.361, 0.753));
  out.viewpoint(Vec3(-1.6, 1.6, 1.7), Vec3(0, 0, 0), Vec3(0, 0, 1), 45.0, 0.01, 512, 512);
  out.light(Vec3(-100.0, -100.0, 100.0));

  out.color(Color(1, 1, 1), 0.1, 0.1, 6.7, 0.9, 1.5);  // clear crystal
  outputSpheres(out, Vec3(-0.8, 0.8, 1.0), 0.17);

  out.color(Color(0.5, 0.45, 0.35), 1.0, 0.0, 0.0, 0.0, 0.0);  // grey rock
  const int points = 1 << size;
  out.reserve(4 + 2 * std::size_t(points) * points);
  const double ratio = 2.0 / std::exp(std::log(2.0) / (kFractalDimension - 1.0));
  const Mountain mountain{out, size, double(points), std::sqrt(ratio * ratio - 1.0)};
  mountain.grow(points, 0, 0, {0.0, 0.0, 0.0, 0.0});
  return std::move(out).finish();
}

}  // namespace raycube::core
