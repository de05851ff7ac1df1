#pragma once
// Tracing one sample's whole ray tree on one thread, against any database query (BruteForce, Bvh): the
// sequential form of what the machine does with messages. Rays are taken from a stack; the order does not
// matter because contributions are summed in fixed point.
#include <cmath>
#include <vector>

#include "core/box.h"
#include "core/contribution_sink.h"
#include "core/intersect.h"
#include "core/precision.h"
#include "core/trace_stats.h"
#include "core/view.h"
#include "core/whitted.h"

namespace raycube::core {

template <class Real>
struct BasicRayTreeScratch {
  BasicRayOutcome<Real> outcome;
  std::vector<BasicTracedRay<Real>> pending;
  std::vector<Hit> crossed;
  std::vector<std::uint32_t> lastBlocker;      // per light: Haines' shadow cache
  std::vector<BasicBox<Real>> lastBlockerBox;  // its box, padded as the BVHs' leaves hold it
};
using RayTreeScratch = BasicRayTreeScratch<double>;

// A database's transmission() leaves the opaque object that blocked a light ray in `crossed`; in a scene
// without transmission that object is tried first for the next light ray to the same light (shadow
// cache): it blocks again more often than not, and any blocker gives the same answer, 0.
// The cache answers only where the database would have met the object: its ray crosses the object's box.
// Where a hit lies off that box (a small object seen from 1e38 away in double, whose test is noise) a BVH
// culls what the test alone finds, and the answer depended on which blocker a processor or worker thread
// had met last: on thread timing (issue 41). A BVH's boxes hold this one, and slab tests grow with their
// box, so the cache never answers otherwise than the database behind it.
template <class Database, class Real>
double lightRayTransmission(const Whitted& shading, const Database& database, const BasicTracedRay<Real>& ray,
                            TraceCounters& counters, BasicRayTreeScratch<Real>& scratch) {
  if (shading.sceneTransmits()) return database.transmission(ray.ray, counters, scratch.crossed);
  if (scratch.lastBlocker.size() <= ray.light) {
    scratch.lastBlocker.resize(ray.light + 1u, UINT32_MAX);
    scratch.lastBlockerBox.resize(ray.light + 1u);
  }
  std::uint32_t& cached = scratch.lastBlocker[ray.light];
  if (cached != UINT32_MAX) {
    countTest(counters, shading.scene().objects[cached]);
    Real tEnter;
    if (slabsHit(scratch.lastBlockerBox[ray.light], ray.ray.origin, InverseDirection<Real>(ray.ray.direction),
                 ray.ray.tMin, ray.ray.tMax, tEnter) &&
        nearestHit(shading.scene().objects[cached], ray.ray, ray.ray.tMax) < kInfinity)
      return 0;
  }
  const double transmission = database.transmission(ray.ray, counters, scratch.crossed);
  if (transmission == 0 && !scratch.crossed.empty() && scratch.crossed.back().object != cached) {
    cached = scratch.crossed.back().object;
    scratch.lastBlockerBox[ray.light] =
        boundsOf(shading.scene().objects[cached], kBoxPaddingRelativeOf<Real>).template enclosingIn<Real>();
  }
  return transmission;
}

// Sees every ray of the tree once it is traced: where it ended (hit, light, or infinity) and the work it
// cost.
struct IgnoreRays {
  template <class Real>
  void operator()(const BasicTracedRay<Real>&, double /*tEnd*/, std::uint64_t /*work*/) const {}
};

template <class Database, class Real, class Observer = IgnoreRays>
void traceRayTree(const Whitted& shading, const Database& database, const BasicTracedRay<Real>& eye,
                  ContributionSink& sink, TraceCounters& counters, BasicRayTreeScratch<Real>& scratch,
                  Observer&& observe = {}) {
  scratch.pending.clear();
  scratch.pending.push_back(eye);
  while (!scratch.pending.empty()) {
    const BasicTracedRay<Real> ray = scratch.pending.back();
    scratch.pending.pop_back();
    ++counters.of(ray.kind);
    scratch.outcome.clear();
    const std::uint64_t workBefore = counters.intersectionTests + counters.boxTests;
    double tEnd = ray.ray.tMax;
    if (ray.kind == RayKind::Light) {
      shading.finishLightRay(ray, lightRayTransmission(shading, database, ray, counters, scratch),
                             scratch.outcome);
    } else {
      const Hit hit = database.closestHit(ray.ray, counters);
      tEnd = hit.t;
      if (hit.found())
        shading.shadeHit(ray, hit, scratch.outcome);
      else
        shading.shadeMiss(ray, scratch.outcome);
    }
    observe(ray, tEnd, counters.intersectionTests + counters.boxTests - workBefore);
    for (const Contribution& c : scratch.outcome.contributions) {
      ++counters.contributions;
      if (!std::isfinite(c.value.x + c.value.y + c.value.z)) ++counters.nonFinite;
      sink.add(c);
    }
    for (const BasicTracedRay<Real>& r : scratch.outcome.spawned) scratch.pending.push_back(r);
  }
}

// The k-th eye ray of sample (sx, sy) as the root of its tree, computed in double and rounded to Real. Its
// coeff is 1 / (rays per sample): each of a sample's rays brings that share of the sample's colour, as every
// contribution carries coeff.
template <class Real = double>
BasicTracedRay<Real> eyeRayOf(const View& view, int sx, int sy, int k = 0) {
  BasicTracedRay<Real> r;
  r.ray = view.eyeRay(sx, sy, k).template as<Real>();
  r.sample = view.sampleIndex(sx, sy);
  r.kind = RayKind::Eye;
  r.depth = 1;
  r.coeff = Real(1.0 / view.raysPerSample());
  return r;
}

}  // namespace raycube::core
