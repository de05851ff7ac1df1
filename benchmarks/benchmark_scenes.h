#pragma once
// The scene the whole-render benchmarks share: the paper's balls (sphereflake) size 2, built once.
#include "core/spd/balls.h"

namespace raycube::benchmarks {

inline const core::Scene& balls2() {
  static const core::Scene scene = core::makeBalls(2);
  return scene;
}

}  // namespace raycube::benchmarks
