#pragma once
// Built-in generator of the SPD "balls" scene (sphereflake), so the classic benchmark needs no file.
#include "core/scene.h"

namespace raycube::core {

// Largest accepted size: 9^6 + ... + 1 = 597871 spheres; size 7 would be over five million.
inline constexpr int kMaxBallsSize = 6;

// The scene Eric Haines' SPD balls.c prints with "-s size" in NFF: size is the recursion depth
// (1 -> 10 spheres, 2 -> 91, 3 -> 820, 4 -> 7381), plus the floor polygon, 3 lights, 2 materials.
// Objects come in balls.c's output order (floor, then the spheres depth first), so the result matches
// shared/scenes/balls<size>.nff. Scene::name is "balls<size>".
// Throws std::invalid_argument unless 1 <= size <= kMaxBallsSize.
Scene makeBalls(int size);

}  // namespace raycube::core
