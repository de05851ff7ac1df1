#pragma once
// A ray in the eye frame, where every region and cell is a box (Priol & Bouatouch 3.3, figure 4):
// x right, y down, z depth; a point's screen coordinates are s = x/z (columns) and q = y/z (rows).
// A face of a region or cell is a plane through the eye (s or q constant) or a plane of constant depth.
// Along a ray s(t) and q(t) are monotone wherever z > 0, so a ray crosses each face at most once there.
#include <cmath>

#include "core/ray.h"
#include "core/tolerances.h"
#include "core/view.h"

namespace raycube::node {

using core::Vec3;

// A point's coordinates in the eye frame (y down), and back to world space.
inline Vec3 eyeFramePoint(const core::View& view, const Vec3& world) {
  Vec3 e = view.toEye(world);
  e.y = -e.y;
  return e;
}
inline Vec3 worldFromEyeFrame(const core::View& view, const Vec3& e) {
  return view.fromCamera(Vec3(e.x, -e.y, e.z));
}

struct EyeFrameRay {
  Vec3 o;  // origin in the eye frame
  Vec3 d;  // direction in the eye frame

  // A float ray is converted exactly to double: the walk is in double whatever the ray's precision.
  template <class Real>
  static EyeFrameRay of(const core::BasicRay<Real>& ray, const core::View& view) {
    Vec3 d = view.directionToEye(Vec3(ray.direction));
    d.y = -d.y;
    return EyeFrameRay{eyeFramePoint(view, Vec3(ray.origin)), d};
  }

  double zAt(double t) const { return o.z + t * d.z; }
  // Screen coordinate along axis 0 (s) or 1 (q) at t; at or behind the eye plane, the limit from the
  // front side: +-infinity, or d/dz when the ray crosses the eye plane exactly on the axis.
  double screenAt(int axis, double t) const {
    const double z = zAt(t);
    const double a = o[axis] + t * d[axis];
    if (z > 0) return a / z;
    if (a == 0 || d.z == 0) return d.z != 0 ? d[axis] / d.z : 0.0;
    return std::copysign(core::kInfinity, a * d.z);
  }
  // +1 / -1 / 0: the sign of ds/dt (axis 0) or dq/dt (axis 1) in front of the eye.
  int screenDirection(int axis) const {
    const double w = d[axis] * o.z - o[axis] * d.z;
    return (w > 0) - (w < 0);
  }
  // t where the ray meets the plane (screen coordinate = c) in front of the eye; infinity if it does not.
  double planeCrossing(int axis, double c) const {
    const double t = (c * o.z - o[axis]) / (d[axis] - c * d.z);
    if (!std::isfinite(t)) return core::kInfinity;
    const double scale = std::abs(o.z) + std::abs(t * d.z);
    return zAt(t) > core::kApexRelative * scale ? t : core::kInfinity;
  }
  // t where the ray meets the depth plane z = c; infinity if parallel.
  double depthCrossing(double c) const {
    const double t = (c - o.z) / d.z;
    return std::isfinite(t) ? t : core::kInfinity;
  }

  // The ray's t-line splits at the eye plane into a part in front of the eye (z > 0), owned by the
  // regions, and a rear part, owned by every node (see RearSpace).
  double eyePlaneCrossing() const { return d.z != 0 ? -o.z / d.z : core::kInfinity; }
  bool inFront(double t) const {
    if (d.z > 0) return t >= eyePlaneCrossing();
    if (d.z < 0) return t < eyePlaneCrossing();
    return o.z > 0;
  }
  // End of the part (front or rear) containing t.
  double partEnd(double t) const {
    const double tz = eyePlaneCrossing();
    return (d.z != 0 && tz > t) ? tz : core::kInfinity;
  }
  // Whether the part containing t is the last the ray's interval [.., tMax] reaches: nothing is traced
  // beyond it, whether tMax or the end of the line ends it. A NaN tMax (a ray of garbage numbers) ends
  // every part: a walk that asked for one more would ask again forever.
  bool lastPart(double t, double tMax) const { return !(partEnd(t) < tMax); }
};

}  // namespace raycube::node
