#pragma once
// Axis-aligned boxes: bounding volumes for the BVH and for the machine's region/cell assignment.
#include <algorithm>
#include <cmath>

#include "core/ray.h"
#include "core/tolerances.h"

namespace raycube::core {

struct Box {
  Vec3 lo{kInfinity, kInfinity, kInfinity};
  Vec3 hi{-kInfinity, -kInfinity, -kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  Vec3 center() const { return 0.5 * (lo + hi); }
  Vec3 extent() const { return hi - lo; }
  // Grown by kBoxPaddingRelative of its size and magnitude: conservative against rounding.
  Box padded() const {
    const Vec3 magnitude = glm::max(glm::abs(lo), glm::abs(hi));
    const Vec3 pad = kBoxPaddingRelative * (extent() + magnitude);
    return Box{lo - pad, hi + pad};
  }
};

// Reciprocal direction for slab tests; IEEE gives +-inf for zero components, which the test handles.
struct InverseDirection {
  explicit InverseDirection(const Vec3& d) : inv(1.0 / d.x, 1.0 / d.y, 1.0 / d.z) {}
  Vec3 inv;
};

// Robust slab test (Ize, "Robust BVH ray traversal", 2013): no NaN from 0*inf because an origin exactly on
// a slab plane with a zero direction component gives (0 * inf) only when the box is degenerate, which
// padded() rules out; the far distance is widened by 2 gamma(3) so rounding never culls a true hit.
inline bool slabsHit(const Box& box, const Vec3& origin, const InverseDirection& id, double tMin,
                     double tMax, double& tEnter) {
  double t0 = tMin, t1 = tMax;
  for (int a = 0; a < 3; ++a) {
    double tNear = (box.lo[a] - origin[a]) * id.inv[a];
    double tFar = (box.hi[a] - origin[a]) * id.inv[a];
    if (tNear > tFar) std::swap(tNear, tFar);
    tFar *= 1 + 2 * 3 * 0x1p-53;
    // NaN (0 * inf) comparisons are false, leaving t0/t1 unchanged: the slab does not constrain.
    t0 = tNear > t0 ? tNear : t0;
    t1 = tFar < t1 ? tFar : t1;
    if (t0 > t1) return false;
  }
  tEnter = t0;
  return true;
}

}  // namespace raycube::core
