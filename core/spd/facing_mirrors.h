#pragma once
// Built-in generator of two facing mirrors (issue 6, "Weights underflow"): every eye ray bounces between
// them for the whole tree depth, so its Ks product runs down to denormals and zero when Ks is small.
#include "core/scene.h"

namespace raycube::core {

// Bounces every eye ray makes before it could escape past the mirrors' edges (about 150 with this
// geometry); a depth-64 tree hits a mirror at every one of its 64 levels.
inline constexpr int kFacingMirrorsMinBounces = 64;

// Two parallel 200 x 200 square mirrors at z = -1 and z = +1, both with material (white, Kd 0.1, Ks = ks,
// Shine 10, T 0), one uncoloured light at (0, 0, 0.5) between them, and the camera at the origin looking
// at the z = -1 mirror about 6 degrees off its normal with a 20-degree field of view. Background black.
// Scene::name is "facing_mirrors". Throws std::invalid_argument unless 0 <= ks <= 1.
Scene makeFacingMirrors(double ks);

}  // namespace raycube::core
