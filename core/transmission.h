#pragma once
// transmission(P -> light): the product of T over the objects a light ray crosses, taken in (t, object)
// order so that every renderer, and every chain of processors a light ray visits, multiplies the same
// numbers in the same order and gets the same bits. An opaque object makes it 0.
#include <algorithm>
#include <vector>

#include "core/intersect.h"
#include "core/whitted.h"

namespace raycube::core {

// Multiply `transmission` by the transmissions of `crossed` (sorted here); 0 at the first opaque one.
inline double transmissionThrough(double transmission, std::vector<Hit>& crossed, const Whitted& shading) {
  std::sort(crossed.begin(), crossed.end(), [](const Hit& a, const Hit& b) { return a.closerThan(b); });
  for (const Hit& h : crossed) {
    const double t = shading.transmissionOf(h.object);
    if (t <= 0) return 0;
    transmission *= t;
  }
  return transmission;
}

}  // namespace raycube::core
