#pragma once
// Vectors of the renderer: GLM double precision, one alias so the rest of core reads plainly.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace raycube::core {

using Vec3 = glm::dvec3;
using Color = glm::dvec3;

}  // namespace raycube::core
