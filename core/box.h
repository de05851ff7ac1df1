#pragma once
// Axis-aligned boxes: bounding volumes for the BVH and for the machine's region/cell assignment. Box is the
// double one; the BVH keeps its nodes in the precision of the rays it tests (BasicBox<Real>).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/ray.h"
#include "core/tolerances.h"

namespace raycube::core {

template <class Real>
struct BasicBox {
  static constexpr Real kInf = std::numeric_limits<Real>::infinity();
  Vec3Of<Real> lo{kInf, kInf, kInf};
  Vec3Of<Real> hi{-kInf, -kInf, -kInf};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  // Whether p lies in the box, faces included.
  bool holds(const Vec3Of<Real>& p) const {
    return glm::all(glm::lessThanEqual(lo, p)) && glm::all(glm::lessThanEqual(p, hi));
  }
  void extend(const Vec3Of<Real>& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const BasicBox& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  Vec3Of<Real> center() const { return Real(0.5) * (lo + hi); }
  Vec3Of<Real> extent() const { return hi - lo; }
  // Half the surface area (the surface-area heuristic's measure); 0 for an empty box.
  Real halfArea() const {
    if (empty()) return 0;
    const Vec3Of<Real> e = extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
  // Grown on every side by `relative` of its largest extent plus its largest coordinate magnitude, over all
  // three axes: conservative against rounding, which in one axis depends on the coordinates of the others.
  // A flat box at 0 (a polygon in the plane z = 0) thus gets a margin across its plane too: without it the
  // slab test's entry could round past the polygon's own hit and the traversal drop a tied object.
  BasicBox padded(double relative) const {
    const Vec3Of<Real> scale = extent() + glm::max(glm::abs(lo), glm::abs(hi));
    const Real pad = Real(relative) * std::max({scale.x, scale.y, scale.z});
    return BasicBox{lo - pad, hi + pad};
  }
  // The box in another precision, rounded outwards so that it still holds everything this one holds.
  template <class To>
  BasicBox<To> enclosingIn() const {
    BasicBox<To> out{Vec3Of<To>(lo), Vec3Of<To>(hi)};
    for (int a = 0; a < 3; ++a) {
      if (Real(out.lo[a]) > lo[a]) out.lo[a] = std::nextafter(out.lo[a], -BasicBox<To>::kInf);
      if (Real(out.hi[a]) < hi[a]) out.hi[a] = std::nextafter(out.hi[a], BasicBox<To>::kInf);
    }
    return out;
  }
};
using Box = BasicBox<double>;

// A ray prepared for many slab tests: reciprocal direction (IEEE gives +-inf for zero components) and the
// index of the near plane per axis, so the test needs no swaps.
template <class Real>
struct InverseDirection {
  explicit InverseDirection(const Vec3Of<Real>& d) : inv(Real(1) / d.x, Real(1) / d.y, Real(1) / d.z) {
    for (int a = 0; a < 3; ++a) negative[a] = inv[a] < 0;
  }
  Vec3Of<Real> inv;
  bool negative[3];
};

// Robust slab test (Ize, "Robust BVH ray traversal", 2013): the far distance is widened by 2 gamma(3) of the
// precision so rounding never culls a true hit. A NaN from (0 * inf), an origin exactly on the plane of a
// slab the ray runs parallel to, fails every comparison and leaves [t0, t1] unconstrained by that slab.
// [tEnter, tExit]: the part of [tMin, tMax] inside the box, when there is one.
template <class Real>
inline bool slabsSpan(const BasicBox<Real>& box, const Vec3Of<Real>& origin, const InverseDirection<Real>& id,
                      Real tMin, Real tMax, Real& tEnter, Real& tExit) {
  constexpr Real kWidening = 1 + 2 * 3 * (std::numeric_limits<Real>::epsilon() / 2);
  const Vec3Of<Real>* planes = &box.lo;  // planes[0] = lo, planes[1] = hi
  Real t0 = tMin, t1 = tMax;
  for (int a = 0; a < 3; ++a) {
    const Real tNear = (planes[id.negative[a]][a] - origin[a]) * id.inv[a];
    const Real tFar = (planes[!id.negative[a]][a] - origin[a]) * id.inv[a] * kWidening;
    t0 = tNear > t0 ? tNear : t0;
    t1 = tFar < t1 ? tFar : t1;
  }
  tEnter = t0;
  tExit = t1;
  return t0 <= t1;
}

template <class Real>
inline bool slabsHit(const BasicBox<Real>& box, const Vec3Of<Real>& origin, const InverseDirection<Real>& id,
                     Real tMin, Real tMax, Real& tEnter) {
  Real tExit;
  return slabsSpan(box, origin, id, tMin, tMax, tEnter, tExit);
}

}  // namespace raycube::core
