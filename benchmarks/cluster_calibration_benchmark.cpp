// Calibration of the `cluster` platform's node speed (host/machine/platforms/cluster.xml, written by
// generate.sh there): how many of the cost table's flop-equivalents per second one core of this host
// achieves. Time is charged in simulated time from counted work (issue 12: never measured), so the one number
// that ties the cluster to this host is measured here, once, and copied into the platform by hand; no test
// depends on it.
//
//   cluster_calibration_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Two measures of the same thing, on balls 2 at 128x128 (depth 5, pixel centres), over the tracing phase:
// - Machine1x1: the machine on one logical processor (threads, no messages): the very node code the
//   simulation runs and the very counts it prices (NodeStats), so this is the value to use.
// - ImageParallel1Thread: the image-parallel renderer on one thread, its counters priced as if they were a
//   node's (BVH node visits as cell steps; every ray spawned and finished once): a cross-check.
// The counter node_speed is flop-equivalents per second of trace time.
#include <benchmark/benchmark.h>

#include "benchmark_scenes.h"
#include "host/machine/emulated_platform.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"

namespace raycube::host {
namespace {

constexpr int kSide = 128;

using benchmarks::balls2;

RenderSettings oneThread() {
  RenderSettings s;
  s.width = s.height = kSide;
  s.sampling = core::Sampling::Centers;
  s.threads = 1;
  s.progress = false;
  return s;
}

void report(benchmark::State& state, double flops, double traceSeconds) {
  state.counters["node_speed"] = traceSeconds > 0 ? flops / traceSeconds : 0.0;
  state.counters["flop_eq_per_render"] =
      flops / double(std::max<benchmark::IterationCount>(1, state.iterations()));
}

void BM_Machine1x1(benchmark::State& state) {
  MachineSettings machine;
  machine.rows = machine.columns = 1;
  const CostTable costs = builtinPlatform("cluster").costs;
  double flops = 0, seconds = 0;
  for (auto _ : state) {
    MachineReport out;
    const RenderResult result = renderMachine(balls2(), oneThread(), machine, &out);
    for (const ProcessorReport& p : out.processors) flops += costs.flopsOf(p.node);
    seconds += result.traceSeconds;
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  report(state, flops, seconds);
}

// The image-parallel counters as one node's: what a processor holding the whole image would count.
node::NodeStats asOneNode(const core::TraceCounters& counters) {
  node::NodeStats n;
  n.processed = counters;
  n.spawned = counters.rays;
  n.finished = counters.rays;
  return n;
}

void BM_ImageParallel1Thread(benchmark::State& state) {
  const CostTable costs = builtinPlatform("cluster").costs;
  double flops = 0, seconds = 0;
  for (auto _ : state) {
    const RenderResult result = renderImageParallel(balls2(), oneThread());
    flops += costs.flopsOf(asOneNode(result.counters));
    seconds += result.traceSeconds;
    benchmark::DoNotOptimize(result.image.pixels.data());
  }
  report(state, flops, seconds);
}

BENCHMARK(BM_Machine1x1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ImageParallel1Thread)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace raycube::host

BENCHMARK_MAIN();
