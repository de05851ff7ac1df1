#include "core/spd/generators.h"

#include <fmt/format.h>

#include <array>
#include <stdexcept>
#include <string>

#include "core/spd/balls.h"

namespace raycube::core {

namespace {

constexpr std::array kGenerators{
    SpdGenerator{"balls", 4, kMaxBallsSize, makeBalls,
                 "sphereflake: 9^0+...+9^s spheres on a floor; 4 -> 7382"},
    SpdGenerator{"jacks", 4, kMaxJacksSize, makeJacks, "recursive jacks of cylinders and spheres; 4 -> 5265"},
    SpdGenerator{"lattice", 12, kMaxLatticeSize, makeLattice,
                 "spheres on a cubic lattice joined by cylinders; 12 -> 8281"},
    SpdGenerator{"mount", 6, kMaxMountSize, makeMount, "fractal mountain and four glass spheres; 6 -> 8196"},
    SpdGenerator{"rings", 7, kMaxRingsSize, makeRings,
                 "pyramid of pentagonal rings before a wall; 7 -> 8401"},
    SpdGenerator{"sombrero", 3, kMaxSombreroSize, makeSombrero,
                 "height field of a damped ripple, triangles; 3 -> 32258"},
    SpdGenerator{"tetra", 6, kMaxTetraSize, makeTetra, "Sierpinski tetrahedron of triangles; 6 -> 4096"},
};

std::string knownNames() {
  std::string names;
  for (const SpdGenerator& generator : kGenerators) {
    names += names.empty() ? "" : ", ";
    names += generator.name;
  }
  return names;
}

}  // namespace

std::span<const SpdGenerator> spdGenerators() {
  return kGenerators;
}

const SpdGenerator& spdGenerator(std::string_view name) {
  for (const SpdGenerator& generator : kGenerators) {
    if (generator.name == name) return generator;
  }
  throw std::invalid_argument(
      fmt::format("unknown SPD scene '{}': the built-in ones are {}", name, knownNames()));
}

Scene makeSpdScene(std::string_view name, int size) {
  const SpdGenerator& generator = spdGenerator(name);
  return generator.make(size == 0 ? generator.defaultSize : size);
}

void requireSpdSize(std::string_view name, int size, int max, std::string_view meaning) {
  if (size < 1 || size > max) {
    throw std::invalid_argument(
        fmt::format("{} size must be from 1 to {} ({}), got {}", name, max, meaning, size));
  }
}

}  // namespace raycube::core
