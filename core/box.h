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

// A ray prepared for many slab tests: reciprocal direction (IEEE gives +-inf for zero components) and the
// index of the near plane per axis, so the test needs no swaps.
struct InverseDirection {
  explicit InverseDirection(const Vec3& d) : inv(1.0 / d.x, 1.0 / d.y, 1.0 / d.z) {
    for (int a = 0; a < 3; ++a) negative[a] = inv[a] < 0;
  }
  Vec3 inv;
  bool negative[3];
};

// Robust slab test (Ize, "Robust BVH ray traversal", 2013): the far distance is widened by 2 gamma(3) so
// rounding never culls a true hit. A NaN from (0 * inf), an origin exactly on the plane of a slab the ray
// runs parallel to, fails every comparison and leaves [t0, t1] unconstrained by that slab.
inline bool slabsHit(const Box& box, const Vec3& origin, const InverseDirection& id, double tMin, double tMax,
                     double& tEnter) {
  const Vec3* planes = &box.lo;  // planes[0] = lo, planes[1] = hi
  double t0 = tMin, t1 = tMax;
  for (int a = 0; a < 3; ++a) {
    const double tNear = (planes[id.negative[a]][a] - origin[a]) * id.inv[a];
    const double tFar = (planes[!id.negative[a]][a] - origin[a]) * id.inv[a] * (1 + 2 * 3 * 0x1p-53);
    t0 = tNear > t0 ? tNear : t0;
    t1 = tFar < t1 ? tFar : t1;
  }
  tEnter = t0;
  return t0 <= t1;
}

}  // namespace raycube::core
