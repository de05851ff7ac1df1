#include "node/eye_box.h"

#include <algorithm>
#include <cmath>

#include "core/intersect.h"
#include "core/tolerances.h"
#include "node/eye_frame_ray.h"

namespace raycube::node {
namespace {

double widen(double v, double magnitude) {
  return core::kCellMarginRelative * (std::abs(v) + magnitude);
}

}  // namespace

EyeBox eyeBoxOf(const core::Object& object, const core::View& view, double sceneExtent) {
  core::Box box;
  if (const auto* sphere = std::get_if<core::Sphere>(&object.shape)) {
    const core::Vec3 c = eyeFramePoint(view, sphere->center);
    box.extend(c - core::Vec3(sphere->radius));
    box.extend(c + core::Vec3(sphere->radius));
  } else if (const auto* polygon = std::get_if<core::Polygon>(&object.shape)) {
    core::forEachBoundingPoint(*polygon, [&](const core::Vec3& v) { box.extend(eyeFramePoint(view, v)); });
  } else if (const auto* patch = std::get_if<core::Patch>(&object.shape)) {
    for (const core::Vec3& v : patch->vertices) box.extend(eyeFramePoint(view, v));
  } else {
    const core::Box world = core::boundsOf(object, core::kCellMarginRelative);
    for (int corner = 0; corner < 8; ++corner)
      box.extend(eyeFramePoint(
          view, core::Vec3(corner & 1 ? world.hi.x : world.lo.x, corner & 2 ? world.hi.y : world.lo.y,
                           corner & 4 ? world.hi.z : world.lo.z)));
  }
  const core::Vec3 size = box.extent();
  const double magnitude = std::max({size.x, size.y, size.z});
  const double hitError = core::kFloatHitErrorRelative * sceneExtent;
  EyeBox eye;
  for (int a = 0; a < 3; ++a) {
    eye.lo[a] = box.lo[a] - widen(box.lo[a], magnitude) - hitError;
    eye.hi[a] = box.hi[a] + widen(box.hi[a], magnitude) + hitError;
  }
  return eye;
}

bool reachesBehindEye(const EyeBox& box) {
  return box.lo.z <= 0;
}

bool mayTouch(const EyeBox& box, const ColumnSlab& slab) {
  const double zLo = std::max(box.lo.z, slab.zLo), zHi = std::min(box.hi.z, slab.zHi);
  if (zLo > zHi) return false;
  // Perspective projection of the clipped box: extremes of a/z over its corners (z > 0), or everything
  // when the clipped box reaches the eye plane.
  auto overlaps = [&](int axis, double lo, double hi) {
    if (zLo <= 0) return true;
    const double margin = core::kCellMarginRelative;
    const double a0 = box.lo[axis], a1 = box.hi[axis];
    const double pLo = std::min(a0 / zLo, a0 / zHi), pHi = std::max(a1 / zLo, a1 / zHi);
    return pLo - margin * (1 + std::abs(pLo)) <= hi && pHi + margin * (1 + std::abs(pHi)) >= lo;
  };
  return overlaps(0, slab.sLo, slab.sHi) && overlaps(1, slab.qLo, slab.qHi);
}

}  // namespace raycube::node
