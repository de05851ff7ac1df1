#include "host/render/sequential_renderers.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <optional>
#include <type_traits>

#include "core/brute_force.h"
#include "core/bvh.h"
#include "core/ray_tree.h"
#include "host/prepare/load_estimate.h"
#include "host/render/framebuffer.h"
#include "host/render/precision_dispatch.h"
#include "host/util/clock.h"
#include "host/util/progress.h"

namespace raycube::host {
namespace {

// Progress that follows the work (rays finished against every ray the image will trace) needs the total:
// estimated from one pixel's tree per 8x8 window (3.7.1's sub-sampling, about 1/64 of a trace), and only
// when progress is shown. `built`: the renderer's own BVH of the scene when it is one in double, traced
// instead of building another.
constexpr int kProgressSubsampleWindow = 8;

void beginTracing(Progress& progress, const core::Scene& scene, const core::View& view,
                  const core::Whitted& shading, bool shown, const core::Bvh* built = nullptr) {
  if (!shown) return progress.phase("tracing");
  progress.phase("estimating");
  const LoadSample sample =
      built ? subsampleLoad(*built, view, shading, kProgressSubsampleWindow, LoadMetric::Rays, true)
            : subsampleLoad(scene, view, shading, kProgressSubsampleWindow, LoadMetric::Rays, true);
  progress.phase("tracing", estimatedTotalRays(sample, view));
}

// Traces sample rows [rowBegin, rowEnd) into the frame buffer, with rays in precision Real.
template <class Real, class Database>
void traceRows(const core::View& view, const core::Whitted& shading, const Database& database, int rowBegin,
               int rowEnd, Framebuffer& frame, core::TraceCounters& counters, Progress& progress) {
  core::BasicRayTreeScratch<Real> scratch;
  for (int sy = rowBegin; sy < rowEnd; ++sy) {
    const std::uint64_t before = counters.totalRays();
    for (int sx = 0; sx < view.samplesX(); ++sx)
      for (int k = 0; k < view.raysPerSample(); ++k)
        core::traceRayTree(shading, database, core::eyeRayOf<Real>(view, sx, sy, k), frame, counters,
                           scratch);
    progress.advance(counters.totalRays() - before);
  }
}

template <class Real>
RenderResult renderReferenceIn(const core::Scene& scene, const RenderSettings& settings) {
  Progress progress("preparing", 0, settings.progress);
  const auto start = Clock::now();
  const core::View view(scene.camera, settings.width, settings.height, settings.sampling,
                        settings.shading.raysPerSample);
  const core::Whitted shading(scene, settings.shading);
  const core::BruteForce database(scene, shading);
  Framebuffer frame(view.samplesX(), view.samplesY());
  RenderResult result;
  result.mode = "reference";
  result.precision = core::kPrecisionOf<Real>;
  result.preprocessSeconds = secondsSince(start);
  beginTracing(progress, scene, view, shading, settings.progress);
  const auto traceStart = Clock::now();
  traceRows<Real>(view, shading, database, 0, view.samplesY(), frame, result.counters, progress);
  result.image = frame.resolve(view);
  result.traceSeconds = secondsSince(traceStart);
  return result;
}

template <class Real>
RenderResult renderImageParallelIn(const core::Scene& scene, const RenderSettings& settings) {
  Progress progress("building the BVH", 0, settings.progress);
  const auto start = Clock::now();
  std::optional<tbb::global_control> limit;
  if (settings.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, settings.threads);
  const core::View view(scene.camera, settings.width, settings.height, settings.sampling,
                        settings.shading.raysPerSample);
  const core::Whitted shading(scene, settings.shading);
  const core::BasicBvh<Real> database(scene, shading,
                                      settings.threads == 1 ? core::BasicBvh<Real>::BuildOn::OneCore
                                                            : core::BasicBvh<Real>::BuildOn::EveryCore);
  Framebuffer frame(view.samplesX(), view.samplesY());
  RenderResult result;
  result.mode = "image-parallel";
  result.precision = core::kPrecisionOf<Real>;
  result.workers = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  result.preprocessSeconds = secondsSince(start);
  const core::Bvh* built = nullptr;
  if constexpr (std::is_same_v<Real, double>) built = &database;
  beginTracing(progress, scene, view, shading, settings.progress, built);
  const auto traceStart = Clock::now();
  tbb::combinable<core::TraceCounters> counters;
  // Each sample row belongs to exactly one task, so frame buffer slots never have two writers. Every task
  // releases its rows and the host acquires them all after the join: the join already orders them, but in
  // Debian's oneTBB, built without ThreadSanitizer, invisibly to it.
  std::atomic<int> tasksDone{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, view.samplesY(), 4), [&](const tbb::blocked_range<int>& rows) {
    traceRows<Real>(view, shading, database, rows.begin(), rows.end(), frame, counters.local(), progress);
    tasksDone.fetch_add(1, std::memory_order_release);
  });
  (void)tasksDone.load(std::memory_order_acquire);
  counters.combine_each([&](const core::TraceCounters& c) { result.counters += c; });
  result.image = frame.resolve(view);
  result.traceSeconds = secondsSince(traceStart);
  return result;
}

}  // namespace

RenderResult renderReference(const core::Scene& scene, const RenderSettings& settings) {
  return renderInPrecision(scene, settings.precision, [&]<class Real>(const core::Scene& traced) {
    return renderReferenceIn<Real>(traced, settings);
  });
}

RenderResult renderImageParallel(const core::Scene& scene, const RenderSettings& settings) {
  return renderInPrecision(scene, settings.precision, [&]<class Real>(const core::Scene& traced) {
    return renderImageParallelIn<Real>(traced, settings);
  });
}

}  // namespace raycube::host
