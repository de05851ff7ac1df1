#pragma once
// Where the scene lies (MachineContext::sceneBounds): a few world boxes holding every object. A ray that
// cannot meet them again has nothing left to hit, wherever it goes: the processor it is in ends it, instead
// of passing it through empty regions to the screen's edge; the host's load estimate ends its sub-sampled
// twin at the same place (host/prepare/load_estimate.h).
#include <algorithm>
#include <optional>
#include <vector>

#include "core/box.h"

namespace raycube::node {

// The last t of [t, tMax] at which the ray (origin + t direction) is inside one of the boxes; none when it
// meets none of them there. The slab test is conservative: a ray it rules out cannot touch a box.
inline std::optional<double> lastInsideBounds(const std::vector<core::Box>& bounds, const core::Vec3& origin,
                                              const core::Vec3& direction, double t, double tMax) {
  const core::InverseDirection<double> inverse(direction);
  std::optional<double> last;
  for (const core::Box& box : bounds) {
    double tEnter, tExit;
    if (core::slabsSpan(box, origin, inverse, t, tMax, tEnter, tExit) && !(last && *last >= tExit))
      last = tExit;
  }
  return last;
}

// Whether the ray meets one of the boxes within [t, tMax]: lastInsideBounds(...) has a value, found at the
// first box met (a processor asks this at every region exit).
inline bool meetsBounds(const std::vector<core::Box>& bounds, const core::Vec3& origin,
                        const core::Vec3& direction, double t, double tMax) {
  // Most rays leave a region with objects still around them: a point inside a box settles it, without the
  // slab test's divisions (rounding at a box's face can only keep a ray going, never end one early).
  const core::Vec3 at = origin + t * direction;
  if (t <= tMax &&
      std::any_of(bounds.begin(), bounds.end(), [&](const core::Box& box) { return box.holds(at); }))
    return true;
  const core::InverseDirection<double> inverse(direction);
  double tEnter;
  for (const core::Box& box : bounds)
    if (core::slabsHit(box, origin, inverse, t, tMax, tEnter)) return true;
  return false;
}

}  // namespace raycube::node
