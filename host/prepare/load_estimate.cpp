#include "host/prepare/load_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/bvh.h"
#include "core/ray_tree.h"
#include "host/util/parallel_for.h"
#include "node/scene_bounds.h"

namespace raycube::host {
namespace {

// The refined metric: a ray weighs one (its message, walk set-up and shading) plus this share of its work
// relative to the mean ray's. Chosen on the emulated machine's clock, whose time is its balance, over 17
// configurations: less simulated time than smaller or larger shares (the figures:
// benchmarks/results/code_comment_measurements.md). The rays processed drift apart as the work evens out.
constexpr double kWorkShare = 0.5;

// Projects the part of a ray in front of the eye (z >= zNear) between t0 and t1 (t1 may be infinite).
bool projectSegment(const core::View& view, const core::Ray& ray, double t1, double zNear,
                    ScreenSegment& out) {
  core::Vec3 o = view.toEye(ray.origin), d = view.directionToEye(ray.direction);
  double t0 = ray.tMin;
  // Keep z(t) = o.z + t d.z >= zNear.
  if (d.z == 0) {
    if (o.z < zNear) return false;
  } else {
    const double tz = (zNear - o.z) / d.z;
    if (d.z > 0)
      t0 = std::max(t0, tz);
    else
      t1 = std::min(t1, tz);
  }
  if (t0 > t1 || (t0 == t1 && t1 != ray.tMin)) return false;  // t0 == t1 == tMin: the ray's origin only
  auto screen = [&](double t, double& x, double& y) {
    double u, v;
    if (std::isinf(t)) {  // the vanishing point of the direction (d.z > 0 here)
      u = d.x / d.z;
      v = d.y / d.z;
    } else {
      const core::Vec3 p = o + t * d;
      u = p.x / p.z;
      v = p.y / p.z;
    }
    x = view.boundaryIndexU(u);
    y = view.boundaryIndexV(v);
  };
  screen(t0, out.x0, out.y0);
  screen(t1, out.x1, out.y1);
  // Regions at the edges extend to infinity: what projects beyond the screen lands on its border.
  const double w = view.samplesX(), h = view.samplesY();
  out.x0 = std::clamp(out.x0, 0.0, w);
  out.x1 = std::clamp(out.x1, 0.0, w);
  out.y0 = std::clamp(out.y0, 0.0, h);
  out.y1 = std::clamp(out.y1, 0.0, h);
  return std::isfinite(out.x0 + out.x1 + out.y0 + out.y1);
}

}  // namespace

LoadSample subsampleLoad(const core::Scene& scene, const core::View& view, const core::Whitted& shading,
                         int window, LoadMetric metric, bool lightRaysWhereTheyStart,
                         const std::vector<core::Box>& sceneBounds) {
  return subsampleLoad(core::Bvh(scene, shading), view, shading, window, metric, lightRaysWhereTheyStart,
                       sceneBounds);
}

LoadSample subsampleLoad(const core::Bvh& database, const core::View& view, const core::Whitted& shading,
                         int window, LoadMetric metric, bool lightRaysWhereTheyStart,
                         const std::vector<core::Box>& sceneBounds) {
  const double zNear = std::max(view.hither(), 1e-9 * (1 + glm::length(view.eye())));
  // One sample per window, at its centre (3.7.1: "choosing one pixel in each window"); the rows of windows
  // on all cores, then joined in order, so the segments come in the same order however many cores ran.
  const int windowRows = (view.samplesY() + window - 1) / window;
  std::vector<LoadSample> rows{std::size_t(windowRows)};
  parallelFor(windowRows, [&](int wy) {
    LoadSample& row = rows[std::size_t(wy)];
    core::DiscardContributions colours;
    core::TraceCounters& counters = row.traced;
    core::RayTreeScratch scratch;
    auto record = [&](const core::TracedRay& ray, double tEnd, std::uint64_t work) {
      ++row.raysTraced;
      ScreenSegment s;
      const bool point = lightRaysWhereTheyStart && ray.kind == core::RayKind::Light;
      // An eye ray projects onto its pixel whatever its length (and the eye itself has no projection); the
      // others end where they leave the scene's bounds, or stay the point they start from.
      if (!point && !sceneBounds.empty() && ray.kind != core::RayKind::Eye)
        tEnd = std::min(tEnd, node::lastInsideBounds(sceneBounds, core::Vec3(ray.ray.origin),
                                                     core::Vec3(ray.ray.direction), ray.ray.tMin, tEnd)
                                  .value_or(ray.ray.tMin));
      if (!projectSegment(view, ray.ray, point ? ray.ray.tMin : tEnd, zNear, s)) return;
      s.work = double(work);
      s.weight = metric == LoadMetric::Rays ? 1.0 : 1 + s.work;
      row.segments.push_back(s);
    };
    for (int wx = 0; wx * window < view.samplesX(); ++wx) {
      const int sx = std::min(view.samplesX() - 1, wx * window + window / 2);
      const int sy = std::min(view.samplesY() - 1, wy * window + window / 2);
      core::traceRayTree(shading, database, core::eyeRayOf(view, sx, sy), colours, counters, scratch, record);
      ++row.pixelsSampled;
    }
  });
  LoadSample sample;
  sample.raysPerSegment = double(window) * window;
  std::size_t segments = 0;
  for (const LoadSample& row : rows) segments += row.segments.size();
  sample.segments.reserve(segments);
  for (const LoadSample& row : rows) {
    sample.segments.insert(sample.segments.end(), row.segments.begin(), row.segments.end());
    sample.raysTraced += row.raysTraced;
    sample.pixelsSampled += row.pixelsSampled;
    sample.traced += row.traced;
  }
  if (metric == LoadMetric::Cost && !sample.segments.empty()) {
    // A ray counts one, plus its work relative to the mean ray's: every piece of it costs a message and a
    // walk set-up where it enters a region (clipSegment keeps the one whole), and some rays much more in
    // intersection tests.
    double mean = 0;
    for (const ScreenSegment& s : sample.segments) mean += s.weight;
    mean /= double(sample.segments.size());
    for (ScreenSegment& s : sample.segments) s.weight = 1 + kWorkShare * s.weight / mean;
  }
  return sample;
}

int subsampleWindowFor(int samplesX, int samplesY, int processors) {
  // Measured on the emulated iPSC/1, balls 2 at 128x128 on 32 processors (benchmarks/host_time.sh):
  constexpr double kHostShare =
      2.0;  // h: the sub-sample and its BSP per sampled pixel, against T1's per pixel
  constexpr double kCoarseness = 1.2;  // c: the busiest region's excess per unit of w sqrt(P / S)
  const double samples = double(samplesX) * samplesY;
  const double w = std::cbrt(2 * kHostShare / kCoarseness * std::sqrt(double(processors) * samples));
  return std::clamp(int(std::lround(w)), 1, std::max(1, std::min(samplesX, samplesY)));
}

double estimatedTotalRays(const LoadSample& sample, const core::View& view) {
  if (sample.pixelsSampled == 0) return 0;
  const double samples = double(view.samplesX()) * view.samplesY() * view.raysPerSample();
  return double(sample.raysTraced) / double(sample.pixelsSampled) * samples;
}

namespace {

// The part of a segment inside a rectangle (Liang-Barsky), weighing what the segment weighs, and the fraction
// of its length kept; false when none.
bool clipKeeping(const ScreenSegment& in, double x0, double y0, double x1, double y1, ScreenSegment& out,
                 double& kept) {
  const double dx = in.x1 - in.x0, dy = in.y1 - in.y0;
  double a = 0, b = 1;
  auto edge = [&](double p, double q) {  // keep where p * t <= q
    if (p == 0) return q >= 0;
    const double r = q / p;
    if (p < 0)
      a = std::max(a, r);
    else
      b = std::min(b, r);
    return a <= b;
  };
  if (!(edge(-dx, in.x0 - x0) && edge(dx, x1 - in.x0) && edge(-dy, in.y0 - y0) && edge(dy, y1 - in.y0)))
    return false;
  out = ScreenSegment{in.x0 + a * dx, in.y0 + a * dy, in.x0 + b * dx, in.y0 + b * dy, in.weight, in.work};
  kept = b - a;
  return true;
}

// What a piece keeping `kept` of a segment of this weight weighs in the metric (a point keeps it whole).
double pieceWeight(const ScreenSegment& in, double weight, double kept, LoadMetric metric) {
  const bool point = in.x1 == in.x0 && in.y1 == in.y0;
  return metric == LoadMetric::Cost && !point ? costOfPiece(weight, kept) : weight;
}

}  // namespace

bool clipSegment(const ScreenSegment& in, double x0, double y0, double x1, double y1, LoadMetric metric,
                 ScreenSegment& out) {
  double kept;
  if (!clipKeeping(in, x0, y0, x1, y1, out, kept)) return false;
  out.weight = pieceWeight(in, in.weight, kept, metric);
  return true;
}

namespace {

// The areas overlapping each bucket of a coarse grid over the screen, so that a segment is clipped only
// against the areas near it (64 areas by a hundred thousand sub-sampled segments otherwise).
class AreaBuckets {
 public:
  explicit AreaBuckets(const std::vector<node::SampleRect>& areas) {
    for (const node::SampleRect& a : areas) {
      width_ = std::max(width_, a.x1);
      height_ = std::max(height_, a.y1);
    }
    bucketWidth_ = std::max(1, (width_ + kBuckets - 1) / kBuckets);
    bucketHeight_ = std::max(1, (height_ + kBuckets - 1) / kBuckets);
    // Each area in the buckets its samples fall in (x0 to x1 - 1): a 64-sample area on 32-sample buckets is
    // in 2 x 2 of them, where its closed rectangle (to x1) would put it in 3 x 3. A segment on an area's far
    // boundary still finds it: a segment's buckets reach a margin beyond its ends (forAreasNear).
    for (std::uint32_t i = 0; i < areas.size(); ++i) {
      const node::SampleRect& a = areas[i];
      for (int by = row(a.y0); by <= row(a.y1 - 1); ++by)
        for (int bx = column(a.x0); bx <= column(a.x1 - 1); ++bx)
          buckets_[std::size_t(by * kBuckets + bx)].push_back(i);
    }
    margin_ = 1e-9 * (1 + width_ + height_);
  }
  int width() const { return width_; }
  int height() const { return height_; }

  // Calls visit(area) once for every area in a bucket the segment's bounding box meets, widened by far more
  // than the clip's rounding: every area whose closed rectangle the clip may find the segment touching.
  template <class Visit>
  void forAreasNear(const ScreenSegment& s, std::vector<std::uint64_t>& seenBy, std::uint64_t stamp,
                    Visit&& visit) const {
    const int bx0 = column(std::min(s.x0, s.x1) - margin_), bx1 = column(std::max(s.x0, s.x1) + margin_);
    const int by0 = row(std::min(s.y0, s.y1) - margin_), by1 = row(std::max(s.y0, s.y1) + margin_);
    for (int by = by0; by <= by1; ++by)
      for (int bx = bx0; bx <= bx1; ++bx)
        for (std::uint32_t area : buckets_[std::size_t(by * kBuckets + bx)])
          if (seenBy[area] != stamp) {
            seenBy[area] = stamp;
            visit(area);
          }
  }

 private:
  static constexpr int kBuckets = 16;
  int column(double x) const { return std::clamp(int(x / bucketWidth_), 0, kBuckets - 1); }
  int row(double y) const { return std::clamp(int(y / bucketHeight_), 0, kBuckets - 1); }

  int width_ = 0, height_ = 0, bucketWidth_ = 1, bucketHeight_ = 1;
  double margin_ = 0;
  std::array<std::vector<std::uint32_t>, kBuckets * kBuckets> buckets_;
};

}  // namespace

AreaEstimates estimateAreas(const std::vector<node::SampleRect>& areas, const LoadSample& sample,
                            LoadMetric metric) {
  AreaEstimates out;
  for (auto* v : {&out.loads, &out.expected.segments, &out.expected.work}) v->assign(areas.size(), 0.0);
  const AreaBuckets near(areas);
  std::vector<std::uint64_t> seenBy(areas.size(), 0);
  std::uint64_t stamp = 0;
  const double n = sample.raysPerSegment;
  // Segments in order, so every area sums its pieces in the order the sub-sampling found them.
  for (const ScreenSegment& s : sample.segments) {
    near.forAreasNear(s, seenBy, ++stamp, [&](std::uint32_t i) {
      const node::SampleRect& a = areas[i];
      ScreenSegment piece;
      double kept;
      // Half-open areas: a piece lying exactly on the far boundary belongs to the next area.
      if (!clipKeeping(s, a.x0, a.y0, a.x1, a.y1, piece, kept)) return;
      if (a.x1 < near.width() && std::min(piece.x0, piece.x1) >= a.x1) return;
      if (a.y1 < near.height() && std::min(piece.y0, piece.y1) >= a.y1) return;
      out.loads[i] += pieceWeight(s, s.weight, kept, metric) * n;
      out.expected.segments[i] += 1.0 * n;
      out.expected.work[i] += pieceWeight(s, 1 + s.work, kept, LoadMetric::Cost) * n;
    });
  }
  return out;
}

}  // namespace raycube::host
