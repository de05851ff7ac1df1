#pragma once
// Priol & Bouatouch 3.7.1, static load distribution, step 1: sub-sample the image (one pixel per w x w
// window), trace those pixels' whole ray trees, and project every ray segment in perspective onto the
// screen. Each projected segment stands for the w x w coherent rays around it.
#include <cstdint>
#include <vector>

#include "core/bvh.h"
#include "core/scene.h"
#include "core/trace_stats.h"
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
  core::TraceCounters traced;       // the sub-sampled rays' tests and BVH steps, by kind (the host's work)
};

// 3.7.1: "the choice of a good sub-sampling ... must depend on the image resolution". The window minimising
// a model of the end-to-end time on `processors` with their own CPUs (benchmarks/results/host_time.md): the
// host pays about h T1 / w^2 for the sub-sample and its BSP (T1 the one-processor time, h measured near 2
// on the emulated iPSC/1), while the busiest region's excess over T1 / P grows as the estimate coarsens,
// about c w sqrt(P / S) of it for S samples (c measured near 1.2). Their sum is least at
// w = cbrt(2 h / c sqrt(P S)): 13 for 128x128 on 32 processors, 21 for 512x512. At least 1, at most the
// screen's shorter side. What does not depend on w (pruning, mapping) does not move it.
int subsampleWindowFor(int samplesX, int samplesY, int processors);

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
