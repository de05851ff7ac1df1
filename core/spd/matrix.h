#pragma once
// The SPD library's 4x4 matrices (Eric Haines' libvec.c conventions), for the built-in SPD generators: they
// act on row vectors, v' = v * M, with the translation in row 3, and a product A * B applies A first. Every
// generator computes with these in the SPD's own order, so its numbers round as the SPD program's do.
#include <array>

#include "core/vec.h"

namespace raycube::core {

using SpdMatrix = std::array<std::array<double, 4>, 4>;

enum class SpdAxis { X, Y, Z };

SpdMatrix spdIdentity();
// lib_create_rotate_matrix: a rotation of `angle` radians about a coordinate axis.
SpdMatrix spdRotation(SpdAxis axis, double angle);
// lib_create_axis_rotate_matrix: about a unit axis (a zero axis gives the identity scaled by cos(angle)).
SpdMatrix spdAxisRotation(const Vec3& axis, double angle);
SpdMatrix spdTranslation(const Vec3& offset);
SpdMatrix spdScaling(const Vec3& factors);
// lib_matrix_multiply: first * then, the transformation that applies `first`, then `then`.
SpdMatrix spdProduct(const SpdMatrix& first, const SpdMatrix& then);

// lib_transform_vector (no translation) and lib_transform_point (with it).
Vec3 spdTransformVector(const Vec3& v, const SpdMatrix& m);
Vec3 spdTransformPoint(const Vec3& p, const SpdMatrix& m);

// lib_normalize_vector: v divided by its length (a zero vector stays as it is).
Vec3 spdNormalized(const Vec3& v);

// lib_tx_unwind's x scale: the length of the first row, which the SPD applies to radii under a transformation
// (it assumes uniform scaling).
double spdScaleOf(const SpdMatrix& m);

}  // namespace raycube::core
