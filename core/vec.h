#pragma once
// Vectors of the renderer: GLM, one alias so the rest of core reads plainly. The scene, the view and the
// machine's geometry are in double; ray state and intersection arithmetic use Vec3Of<Real> for the
// precision the user chose (see core/precision.h).
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace raycube::core {

template <class Real>
using Vec3Of = glm::vec<3, Real, glm::defaultp>;
using Vec3 = Vec3Of<double>;
using Color = glm::dvec3;

}  // namespace raycube::core
