// Issue 6, "Weights underflow": time per traced ray of the facing mirrors at depth 64 (reference renderer,
// one thread, 32x32 pixel centres) by mirror reflectance ks. Each tree carries coeff = ks^(level - 1), so
// a small ks drives it through double denormals (below 2.2e-308) to 0; the target is at most 2x the time
// per ray of ks = 1.
//
//   weight_underflow_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Each benchmark renders ks and ks = 1 alternately in the same loop, so both see the same machine load:
//   ns_per_ray        trace time per traced ray (eye + reflected + shadow) of ks
//   ks1_ns_per_ray    the same for the ks = 1 renders interleaved with them
//   slowdown_vs_ks1   their ratio (the target: <= 2)
//   render_vs_ks1     ratio of whole trace times (small ks spawns fewer light rays: zero weights are
//   skipped)
// denormals:flushed runs both with MXCSR's flush-to-zero and denormals-are-zero bits set: if the slowdown
// disappears there, denormal arithmetic is its cause.
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <xmmintrin.h>

#include <cstdint>
#include <span>
#include <string>

#include "core/spd/facing_mirrors.h"
#include "host/render/sequential_renderers.h"

namespace raycube::host {
namespace {

constexpr int kSide = 32;
// Level at which coeff first is denormal in double: 1e-5 -> 63, 1e-10 -> 32, 1e-160 -> 3; 1e-300 skips
// straight from 1e-300 at level 2 to 0 at level 3. Double's denormals span 16 decades, so at most 3 of 64
// levels carry one. Float's span 7 decades from 1.2e-38: ks = 0.25 reaches them at level 64 (0.25^63 =
// 2^-126), ks = 0.2 at level 56 with 9 levels there, ks = 1e-5 at level 9.
constexpr double kDoubleReflectances[] = {1, 0.999, 0.5, 1e-5, 1e-10, 1e-160, 1e-300};
constexpr double kFloatReflectances[] = {1, 0.999, 0.5, 0.25, 0.2, 1e-5};

enum class Denormals : std::uint8_t { Kept, Flushed };

// Sets FTZ (results) and DAZ (inputs) for this thread while alive; the reference renderer is single-threaded.
class FlushDenormals {
 public:
  explicit FlushDenormals(Denormals mode) : saved_(_mm_getcsr()) {
    constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
    if (mode == Denormals::Flushed) _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
  }
  ~FlushDenormals() { _mm_setcsr(saved_); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned saved_;
};

// Everything but the scene.
RenderSettings mirrorSettings(core::Precision precision) {
  RenderSettings settings;
  settings.precision = precision;
  settings.width = kSide;
  settings.height = kSide;
  settings.sampling = core::Sampling::Centers;
  settings.shading.maxDepth = core::kFacingMirrorsMinBounces;
  settings.shading.minWeight = 0;
  settings.threads = 1;
  settings.progress = false;
  return settings;
}

struct Tally {
  double traceSeconds = 0;
  double rays = 0;
  void add(const RenderResult& result) {
    traceSeconds += result.traceSeconds;
    rays += double(result.counters.totalRays());
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  double nsPerRay() const { return rays > 0 ? 1e9 * traceSeconds / rays : 0.0; }
};

void runAgainstKs1(benchmark::State& state, double ks, const RenderSettings& settings, Denormals mode) {
  const core::Scene scene = core::makeFacingMirrors(ks);
  const core::Scene lossless = core::makeFacingMirrors(1);
  const FlushDenormals flush(mode);
  Tally measured, baseline;
  for (auto _ : state) {
    measured.add(renderReference(scene, settings));
    baseline.add(renderReference(lossless, settings));
  }
  const double renders = double(state.iterations());
  state.counters["ns_per_ray"] = measured.nsPerRay();
  state.counters["ks1_ns_per_ray"] = baseline.nsPerRay();
  state.counters["slowdown_vs_ks1"] = baseline.nsPerRay() > 0 ? measured.nsPerRay() / baseline.nsPerRay() : 0;
  state.counters["render_vs_ks1"] =
      baseline.traceSeconds > 0 ? measured.traceSeconds / baseline.traceSeconds : 0.0;
  state.counters["rays_per_render"] = renders > 0 ? measured.rays / renders : 0.0;
}

void registerBenchmarks(core::Precision precision, std::span<const double> reflectances) {
  for (const Denormals mode : {Denormals::Kept, Denormals::Flushed}) {
    for (const double ks : reflectances) {
      const std::string name =
          fmt::format("FacingMirrorsDepth64/{}/ks:{:g}/denormals:{}", core::nameOf(precision), ks,
                      mode == Denormals::Kept ? "kept" : "flushed");
      benchmark::RegisterBenchmark(name.c_str(), runAgainstKs1, ks, mirrorSettings(precision), mode)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

}  // namespace
}  // namespace raycube::host

int main(int argc, char** argv) {
  raycube::host::registerBenchmarks(raycube::core::Precision::Double, raycube::host::kDoubleReflectances);
  raycube::host::registerBenchmarks(raycube::core::Precision::Float, raycube::host::kFloatReflectances);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
