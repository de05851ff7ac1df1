#pragma once
// Ray-primitive intersection: the nearest crossing of a ray with one object's surface, and the surface
// there. Pure functions of (ray, object), so every renderer and every node finds the same t. Written once
// over the ray's precision Real (float or double): the object's double coordinates are rounded to Real and
// all the arithmetic is done in Real.
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "core/box.h"
#include "core/polygon_outline.h"
#include "core/ray.h"
#include "core/scene.h"
#include "core/trace_stats.h"

namespace raycube::core {

// Nearest t with ray.tMin < t < tMax where the ray meets the object's surface; infinity when none.
template <class Real>
Real nearestHit(const Object& object, const BasicRay<Real>& ray, std::type_identity_t<Real> tMax);

template <class Real>
struct BasicSurfacePoint {
  Vec3Of<Real> point{0, 0, 0};
  Vec3Of<Real> geometricNormal{0, 0, 1};  // unit, outward (as the file orients the surface)
  Vec3Of<Real> shadingNormal{0, 0, 1};    // unit, same side as geometricNormal; interpolated on patches
};
using SurfacePoint = BasicSurfacePoint<double>;

// The surface at a t returned by nearestHit for the same ray.
template <class Real>
BasicSurfacePoint<Real> surfaceAt(const Object& object, const BasicRay<Real>& ray,
                                  std::type_identity_t<Real> t);

// World-space bounding box of the object, padded by paddingRelative of its size and magnitude.
Box boundsOf(const Object& object, double paddingRelative);

// visit(point) for each point whose box bounds every hit on the polygon: its vertices and, for one tested on
// its plane (an outline), the plane's points over them. When the vertices leave the plane (an NFF file's
// rounding, or worse) the hits do too; every structure built on boxes (BVHs, cells, regions) must hold them
// where the reference's brute force finds them. A plane of NaN (collinear vertices) is hit nowhere.
template <class Visit>
void forEachBoundingPoint(const Polygon& polygon, Visit&& visit) {
  for (const Vec3& v : polygon.vertices) visit(v);
  if (polygon.outline)
    for (const Vec3& v : polygon.vertices)
      if (const Vec3 p = polygon.outline->onPlane(v); std::isfinite(p.x + p.y + p.z)) visit(p);
}

// Closest hit of a ray among candidates: smallest t, ties broken by the smaller object index, so that
// any traversal order, any acceleration structure and any partition of space choose the same object.
// t holds a float ray's t exactly.
struct Hit {
  double t = kInfinity;
  std::uint32_t object = UINT32_MAX;

  bool found() const { return object != UINT32_MAX; }
  bool closerThan(const Hit& other) const { return t < other.t || (t == other.t && object < other.object); }
};

// One ray-object test, counted by primitive kind (and, for polygons, by vertex) for the cost models. The
// vertex count is what the paper's iPSC code paid (every vertex, whatever the polygon); raycube's own test of
// a concave polygon looks at the few edges of one band (core/polygon_outline.h), but the emulated machine
// keeps the 1988 cost.
inline void countTest(TraceCounters& counters, const Object& object) {
  ++counters.intersectionTests;
  ++counters.testsByShape[object.shape.index()];
  if (const auto* polygon = std::get_if<Polygon>(&object.shape))
    counters.polygonVerticesTested += polygon->vertices.size();
}

}  // namespace raycube::core
