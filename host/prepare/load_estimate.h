#pragma once
// Priol & Bouatouch 3.7.1, static load distribution, step 1: sub-sample the image (one pixel per w x w
// window), trace those pixels' whole ray trees, and project every ray segment in perspective onto the
// screen. Each projected segment stands for the w x w coherent rays around it.
#include <cstdint>
#include <vector>

#include "core/bvh.h"
#include "core/scene.h"
#include "core/view.h"
#include "core/whitted.h"
#include "host/machine/machine_settings.h"
#include "node/screen_grid.h"

namespace raycube::host {

// A cost-metric weight (one plus a share of work) for the piece holding `fraction` of the ray's projected
// length: the one whole, the share by length.
inline double costOfPiece(double weight, double fraction) {
  return 1 + (weight - 1) * fraction;
}

// A projected ray segment in continuous sample-boundary coordinates (x in [0, samplesX], y in [0, samplesY]).
struct ScreenSegment {
  double x0, y0, x1, y1;
  double weight;    // 1 (rays) or the ray's cost
  double work = 0;  // the sub-sampled ray's traversal steps and intersection tests
};

struct LoadSample {
  std::vector<ScreenSegment> segments;
  double raysPerSegment = 1;  // w * w: how many rays one sub-sampled ray represents
  std::uint64_t raysTraced = 0;
  std::uint64_t pixelsSampled = 0;  // one per window
};

// lightRaysWhereTheyStart: with light cones or pyramids (3.7.2) a light ray is processed only where it
// starts, so it weighs on that point of the screen instead of along its path. sceneBounds: where the
// machine ends rays that leave the scene (node/scene_bounds.h), so a segment ends there too; none: at
// the screen's edge.
LoadSample subsampleLoad(const core::Scene& scene, const core::View& view, const core::Whitted& shading,
                         int window, LoadMetric metric, bool lightRaysWhereTheyStart,
                         const std::vector<core::Box>& sceneBounds = {});
// The same, tracing in a BVH of the whole scene built beforehand (for the shading's scene).
LoadSample subsampleLoad(const core::Bvh& database, const core::View& view, const core::Whitted& shading,
                         int window, LoadMetric metric, bool lightRaysWhereTheyStart,
                         const std::vector<core::Box>& sceneBounds = {});

// Every ray the whole image will trace, eye rays and all their descendants, extrapolated from the
// sub-sampled pixels' trees (each stands for its window, and for every ray per pixel): the total work a
// progress indication compares the rays finished with.
double estimatedTotalRays(const LoadSample& sample, const core::View& view);

// The part of a segment inside a rectangle (Liang-Barsky); false when none. For the ray metric its weight is
// kept whole (figure 9: a split ray counts in both regions); for the cost metric the piece counts one
// whole and the work share above it by the kept fraction of length (costOfPiece).
bool clipSegment(const ScreenSegment& in, double x0, double y0, double x1, double y1, LoadMetric metric,
                 ScreenSegment& out);

// What each area's processor will do, for progress: the ray segments it will evaluate (every piece of a
// split ray counts, as in the ray metric), and their work, each piece weighing one plus its sub-sampled
// twin's steps and tests shared by length (as in the cost metric, unscaled), whatever metric partitioned.
struct ExpectedWork {
  std::vector<double> segments, work;
};

// In one pass over the segments, each area's estimated load in `metric` (the weights of the segment pieces
// inside it, times raysPerSegment) and its processor's expected work.
struct AreaEstimates {
  std::vector<double> loads;
  ExpectedWork expected;
};
AreaEstimates estimateAreas(const std::vector<node::SampleRect>& areas, const LoadSample& sample,
                            LoadMetric metric);

}  // namespace raycube::host
