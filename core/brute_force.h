#pragma once
// The reference database query: every object tested for every ray (the ground truth), in the precision of
// the ray it is asked about.
#include <limits>
#include <vector>

#include "core/intersect.h"
#include "core/trace_stats.h"
#include "core/transmission.h"
#include "core/whitted.h"

namespace raycube::core {

class BruteForce {
 public:
  BruteForce(const Scene& scene, const Whitted& shading) : scene_(scene), shading_(shading) {}

  template <class Real>
  Hit closestHit(const BasicRay<Real>& ray, TraceCounters& counters) const {
    Hit best;
    for (std::uint32_t i = 0; i < scene_.objects.size(); ++i) {
      countTest(counters, scene_.objects[i]);
      const Hit h{nearestHit(scene_.objects[i], ray, std::numeric_limits<Real>::infinity()), i};
      if (h.t < kInfinity && h.closerThan(best)) best = h;
    }
    return best;
  }

  template <class Real>
  double transmission(const BasicRay<Real>& ray, TraceCounters& counters, std::vector<Hit>& crossed) const {
    crossed.clear();
    for (std::uint32_t i = 0; i < scene_.objects.size(); ++i) {
      countTest(counters, scene_.objects[i]);
      const double t = nearestHit(scene_.objects[i], ray, ray.tMax);
      if (t == kInfinity) continue;
      if (!shading_.transmissive(i)) {
        crossed.assign(1, Hit{t, i});  // the blocker, for the caller's shadow cache
        return 0;
      }
      crossed.push_back(Hit{t, i});
    }
    return transmissionThrough(1.0, crossed, shading_);
  }

 private:
  const Scene& scene_;
  const Whitted& shading_;
};

}  // namespace raycube::core
