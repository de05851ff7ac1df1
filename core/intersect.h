#pragma once
// Ray-primitive intersection: the nearest crossing of a ray with one object's surface, and the surface
// there. Pure functions of (ray, object), so every renderer and every node finds the same t.
#include <cstdint>

#include "core/box.h"
#include "core/ray.h"
#include "core/scene.h"

namespace raycube::core {

// Nearest t with ray.tMin < t < tMax where the ray meets the object's surface; kInfinity when none.
double nearestHit(const Object& object, const Ray& ray, double tMax);

struct SurfacePoint {
  Vec3 point{0, 0, 0};
  Vec3 geometricNormal{0, 0, 1};  // unit, outward (as the file orients the surface)
  Vec3 shadingNormal{0, 0, 1};    // unit, same side as geometricNormal; interpolated on patches
};

// The surface at a t returned by nearestHit for the same ray.
SurfacePoint surfaceAt(const Object& object, const Ray& ray, double t);

// Padded world-space bounding box of the object.
Box boundsOf(const Object& object);

// Closest hit of a ray among candidates: smallest t, ties broken by the smaller object index, so that
// any traversal order, any acceleration structure and any partition of space choose the same object.
struct Hit {
  double t = kInfinity;
  std::uint32_t object = UINT32_MAX;

  bool found() const { return object != UINT32_MAX; }
  bool closerThan(const Hit& other) const { return t < other.t || (t == other.t && object < other.object); }
};

}  // namespace raycube::core
