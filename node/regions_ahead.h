#pragma once
// What lies ahead of a ray leaving its region (MachineContext::regionBounds): the regions it would cross
// next, each with the box of the objects it holds. A ray whose part in each of them misses that box, until
// it leaves the scene's bounds or its interval ends, meets nothing more: the processor it is in ends it, as
// the last of them would have, instead of passing it on through regions that only pass it on: the same
// image, fewer messages (mount 6's glass spheres' and mountain's rays leave upwards over the slopes of the
// regions ahead). The test at every region exit costs about the instructions the messages it saves cost;
// the wall time still falls.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/box.h"
#include "core/tolerances.h"
#include "node/eye_frame_ray.h"
#include "node/region_cells.h"
#include "node/region_map.h"
#include "node/scene_bounds.h"

namespace raycube::node {

// Whether the ray (world origin and direction; er, the same in the eye frame), leaving its region at t for
// region `next`, meets no object in the regions of one cell it would cross from there: true where it would
// leave the scene's bounds (sceneBounds) or reach the end of its interval (tMax, or infinity: never the eye
// plane, beyond which the rear objects lie) having missed the box of every region's objects (regionBounds,
// one per region) on its way. False as soon as a part meets a box, and where no face is crossed (a NaN).
inline bool nothingAhead(const RegionMap& regions, const std::vector<core::Box>& regionBounds,
                         const std::vector<core::Box>& sceneBounds, const EyeFrameRay& er,
                         const core::Vec3& origin, const core::Vec3& direction, int next, double t,
                         double tMax) {
  if (regionBounds.empty()) return false;
  // Most rays enter the next region inside the box of its objects (settled without a division).
  if (regionBounds[std::size_t(next)].holds(origin + t * direction)) return false;
  const core::InverseDirection<double> inverse(direction);
  for (int crossed = 0; crossed < regions.processors(); ++crossed) {
    const double tEnd = std::min(er.partEnd(t), tMax);
    const CellPassage p = passageThrough(er, t, tEnd, regions.screenRectOf(next));
    const double widening =
        core::kPartWideningRelative * (std::abs(t) + (std::isfinite(p.end) ? std::abs(p.end) : 0));
    double tEnter;
    if (core::slabsHit(regionBounds[std::size_t(next)], origin, inverse, t - widening, p.end + widening,
                       tEnter))
      return false;
    if (p.reachesEnd) return er.lastPart(t, tMax);
    if (p.exit.sStep == 0 && p.exit.qStep == 0) return false;
    if (!sceneBounds.empty() && !meetsBounds(sceneBounds, origin, direction, p.end, tMax)) return true;
    next = regions.ownerBeyond(next, er, p.end, p.exit.sStep, p.exit.qStep);
    t = p.end;
  }
  return false;
}

}  // namespace raycube::node
