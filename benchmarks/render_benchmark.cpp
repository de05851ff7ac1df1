// Whole renders of the balls2 sphereflake at 128x128 (pixel centres, depth 5): the reference (brute force,
// one thread) and the image-parallel baseline (BVH, oneTBB) with 1 and 2 workers. Time per render, and
// rays/s over the tracing phase (SPD rule 12 separates it from preprocessing).
//
//   render_benchmark --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "benchmark_scenes.h"
#include "host/render/sequential_renderers.h"

namespace raycube::host {
namespace {

constexpr int kSide = 128;

using benchmarks::balls2;

RenderSettings settingsWith(int threads) {
  RenderSettings settings;
  settings.width = kSide;
  settings.height = kSide;
  settings.sampling = core::Sampling::Centers;
  settings.threads = threads;
  settings.progress = false;
  return settings;
}

template <RenderResult (*Render)(const core::Scene&, const RenderSettings&)>
void runRender(benchmark::State& state, int threads) {
  const RenderSettings settings = settingsWith(threads);
  double rays = 0, traceSeconds = 0, preprocessSeconds = 0;
  for (auto _ : state) {
    const RenderResult result = Render(balls2(), settings);
    rays += double(result.counters.totalRays());
    traceSeconds += result.traceSeconds;
    preprocessSeconds += result.preprocessSeconds;
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  const double renders = double(state.iterations());
  state.counters["rays_per_render"] = renders > 0 ? rays / renders : 0.0;
  state.counters["rays_per_s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);  // wall time
  state.counters["trace_rays_per_s"] = traceSeconds > 0 ? rays / traceSeconds : 0.0;
  state.counters["preprocess_ms"] = renders > 0 ? 1e3 * preprocessSeconds / renders : 0.0;
}

void BM_Render_Balls2_Reference(benchmark::State& state) {
  runRender<renderReference>(state, 1);
}
void BM_Render_Balls2_ImageParallel(benchmark::State& state) {
  runRender<renderImageParallel>(state, int(state.range(0)));
}

BENCHMARK(BM_Render_Balls2_Reference)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Render_Balls2_ImageParallel)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace raycube::host

BENCHMARK_MAIN();
