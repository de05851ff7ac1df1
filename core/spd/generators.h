#pragma once
// The SPD (Eric Haines' Standard Procedural Databases) built in: each generator reproduces the NFF its SPD
// program prints with "-s size" in OUTPUT_CURVES mode (the ray-tracing timing format), object for object
// and in the same order, with the same view, lights, materials and background. Scene::name is
// "<name><size>" (rings7, mount6, ...). Every number is rounded as the SPD prints it ("%g"), so written back
// with core/nff_writer.h the scene is the SPD program's text, byte for byte; balls (core/spd/balls.h) is the
// one generator that keeps full doubles.
#include <span>
#include <string_view>

#include "core/scene.h"

namespace raycube::core {

struct SpdGenerator {
  std::string_view name;      // the SPD program: balls, rings, ...
  int defaultSize;            // the size the SPD's testing procedure benchmarks (issue 13's list; jacks.c and
                              // sombrero.c themselves default to 1)
  int maxSize;                // the largest size accepted (the kMax*Size below)
  Scene (*make)(int size);    // throws std::invalid_argument unless 1 <= size <= maxSize
  std::string_view contents;  // one line for --help and README: what the scene holds
};

// Every built-in generator, in alphabetical order.
std::span<const SpdGenerator> spdGenerators();

// The generator called `name`; std::invalid_argument naming the known ones when there is none.
const SpdGenerator& spdGenerator(std::string_view name);

// The SPD scene `name` at `size` (its default size when size is 0). Throws std::invalid_argument for an
// unknown name (listing the known ones) or a size outside 1..maxSize.
Scene makeSpdScene(std::string_view name, int size = 0);

// Largest accepted sizes: beyond them a scene passes about 600,000 primitives (mount: the original hash
// would shift by a negative count).
inline constexpr int kMaxJacksSize = 6;     // 337,041 primitives
inline constexpr int kMaxLatticeSize = 50;  // 132,651 spheres and 390,150 cylinders
inline constexpr int kMaxMountSize = 7;     // 32,772 primitives
inline constexpr int kMaxRingsSize = 30;    // 567,301 primitives
inline constexpr int kMaxSombreroSize = 5;  // 522,242 triangles
inline constexpr int kMaxTetraSize = 9;     // 262,144 triangles

// One generator per SPD program (balls is core/spd/balls.h's makeBalls).
Scene makeRings(int size);     // rings.c: pyramid of s^2+...+1 objects of 30 spheres, 30 cylinders; 7 -> 8401
Scene makeMount(int size);     // mount.c: fractal mountain, 2*4^s triangles + 4 glass spheres; 6 -> 8196
Scene makeTetra(int size);     // tetra.c: Sierpinski tetrahedron, 4^s triangles; 6 -> 4096
Scene makeLattice(int size);   // lattice.c: (s+1)^3 spheres joined by 3s(s+1)^2 cylinders; 12 -> 8281
Scene makeJacks(int size);     // jacks.c: recursive jacks, 9*(8^s-1)/7 spheres and cylinders; 4 -> 5265
Scene makeSombrero(int size);  // sombrero.c: height field, 2*(32*2^(s-1)-1)^2 triangles; 3 -> 32258

// std::invalid_argument "<name> size must be from 1 to <max> (<what the size means>), got <size>" unless
// 1 <= size <= max.
void requireSpdSize(std::string_view name, int size, int max, std::string_view meaning);

}  // namespace raycube::core
