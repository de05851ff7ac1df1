// Progress that tells the truth: named phases, a fraction of the phase's estimated work (never 100% before
// the end, never backwards), one progress line per process that renderers join, a ray estimate close to the
// real count, and the machine's phases and work (threads and simulated time).
#include "host/util/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "core/spd/balls.h"
#include "core/view.h"
#include "core/whitted.h"
#include "host/machine/emulated_platform.h"
#include "host/prepare/load_estimate.h"
#include "host/render/machine_progress.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

TEST(Progress, PhaseWithoutEstimateHasNoFraction) {
  Progress progress(false);
  progress.phase("pruning");
  const ProgressSnapshot s = progress.snapshot();
  EXPECT_EQ(s.phase, "pruning");
  EXPECT_LT(s.fraction, 0);
  EXPECT_LT(s.remainingSeconds, 0);
  EXPECT_EQ(progressLine(s).find('%'), std::string::npos) << progressLine(s);
}

TEST(Progress, FractionFollowsTheWorkAndRestartsWithEachPhase) {
  Progress progress(false);
  progress.phase("tracing", 1000);
  progress.advance(200);
  progress.advance(50);
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.25);
  progress.setWork(600, 1000);
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.6);
  progress.setWork(600, 500);
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.99) << "a lowered estimate: nearly done, not done";
  progress.phase("writing");
  EXPECT_EQ(progress.snapshot().phase, "writing");
  EXPECT_LT(progress.snapshot().fraction, 0);
}

TEST(Progress, NeverClaimsTheEndBeforeIt) {
  Progress progress(false);
  progress.phase("tracing", 100);
  progress.advance(250);  // the estimate was short
  EXPECT_LT(progress.snapshot().fraction, 1.0);
  EXPECT_GE(progress.snapshot().fraction, 0.99);
}

TEST(Progress, NeverGoesBackwardsWithinAPhase) {
  Progress progress(false);
  progress.phase("tracing", 1000);
  progress.setWork(600, 1000);
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.6);
  progress.setWork(400, 1000);  // a late, smaller count
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.6);
  progress.setWork(600, 2000);  // a raised estimate holds the fraction until the work catches up
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.6);
  progress.setWork(1600, 2000);
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.8);
}

TEST(Progress, CompleteMeansAllOfThePhase) {
  Progress progress(false);
  progress.phase("tracing", 1000);
  progress.setWork(10, 1000);
  progress.complete();
  const ProgressSnapshot s = progress.snapshot();
  EXPECT_EQ(s.fraction, 1.0);
  EXPECT_EQ(s.remainingSeconds, 0);
  EXPECT_NE(progressLine(s).find("100%"), std::string::npos) << progressLine(s);
  progress.phase("writing");
  EXPECT_LT(progress.snapshot().fraction, 0) << "complete() belongs to its phase";
}

TEST(Progress, ListenersHearEveryPhaseAndCount) {
  Progress progress(false);
  std::vector<ProgressSnapshot> heard;
  progress.listen([&](const ProgressSnapshot& s) { heard.push_back(s); });
  progress.phase("tracing", 100);
  progress.advance(5);  // the workers' hot path stays silent
  progress.setWork(50, 100);
  progress.complete();
  ASSERT_EQ(heard.size(), 3u);
  EXPECT_EQ(heard[0].phase, "tracing");
  EXPECT_DOUBLE_EQ(heard[1].fraction, 0.5);
  EXPECT_EQ(heard[2].fraction, 1.0);
}

TEST(Progress, RendererHandlesJoinTheOpenLine) {
  Progress line(false);
  line.phase("reading");
  {
    Progress renderer("machine", 400, false);
    EXPECT_EQ(line.snapshot().phase, "machine");
    renderer.advance(100);
    EXPECT_DOUBLE_EQ(line.snapshot().fraction, 0.25);
    renderer.phase("tracing", 1000);
    renderer.advance(500);
  }
  EXPECT_EQ(line.snapshot().phase, "tracing") << "the line goes on after the renderer's handle";
  EXPECT_DOUBLE_EQ(line.snapshot().fraction, 0.5);
}

TEST(Progress, LineReadsAsAUserExpects) {
  ProgressSnapshot s;
  s.phase = "tracing";
  s.fraction = 0.42;
  s.phaseSeconds = 1.2;
  s.remainingSeconds = 95;
  EXPECT_EQ(progressLine(s), "tracing  42%  1.2 s, about 1:35 min left");
}

TEST(Progress, PrintsPhasesAndEndsTheLine) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    Progress progress(true, out, std::chrono::milliseconds(0));
    progress.phase("tracing", 10);
    progress.advance(5);
  }  // the destructor stops the reporter; the last line is always printed
  std::rewind(out);
  std::string text;
  for (int c; (c = std::fgetc(out)) != EOF;) text += char(c);
  std::fclose(out);
  EXPECT_NE(text.find("done in"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
}

TEST(Progress, RayEstimateIsCloseToTheRaysTraced) {
  // The fraction is only as true as its denominator: the sub-sampled estimate of every ray of every tree.
  for (int spp : {1, 4}) {
    const core::Scene scene = core::makeBalls(2);
    RenderSettings settings;
    settings.width = settings.height = 96;
    settings.shading.raysPerSample = spp;
    settings.progress = false;
    const RenderResult result = renderImageParallel(scene, settings);
    const core::View view(scene.camera, settings.width, settings.height, settings.sampling, spp);
    const core::Whitted shading(scene, settings.shading);
    const double estimate =
        estimatedTotalRays(subsampleLoad(scene, view, shading, 8, LoadMetric::Rays, true), view);
    const double actual = double(result.counters.totalRays());
    EXPECT_NEAR(estimate / actual, 1.0, 0.2)
        << "spp " << spp << ": estimate " << estimate << ", traced " << actual;
  }
}

// Each processor's share of the work is its estimated work; how much of it is done, its share of its
// expected segments: a cheap processor finished early does not make the machine look nearly done.
TEST(MachineProgress, WeighsEachProcessorByItsEstimatedWork) {
  ExpectedWork expected;
  expected.segments = {100, 100, 50};
  expected.work = {100, 700, 200};
  const MachineProgress machine(expected);
  EXPECT_EQ(machine.workOf({}).done, 0);
  EXPECT_EQ(machine.workOf({}).expected, 1000);
  // The cheap processor done, the expensive one a tenth of the way, the third halfway.
  const MachineProgress::Work w = machine.workOf({100, 10, 25});
  EXPECT_DOUBLE_EQ(w.done, 100 + 70 + 100);
  EXPECT_EQ(w.expected, 1000);
  EXPECT_DOUBLE_EQ(machine.workOf({500, 100, 50}).done, 1000) << "past its estimate, a processor is done";
}

TEST(MachineProgress, ExpectedWorkFollowsTheSubsampledSegments) {
  LoadSample sample;
  sample.raysPerSegment = 4;
  sample.segments = {{0.5, 0.5, 0.5, 0.5, 1, 9}, {1.5, 0.5, 1.5, 0.5, 1, 0}, {0.5, 0.5, 1.5, 0.5, 1, 3}};
  const ExpectedWork e =
      estimateAreas({{0, 1, 0, 1}, {1, 2, 0, 1}}, sample, LoadMetric::Rays).expected;  // x0, x1, y0, y1
  // A split ray counts whole in each area; of its work, the one (its message and walk set-up) counts whole in
  // each too, its steps and tests by the length in each.
  EXPECT_DOUBLE_EQ(e.segments[0], 4 * 2);
  EXPECT_DOUBLE_EQ(e.segments[1], 4 * 2);
  EXPECT_DOUBLE_EQ(e.work[0], 4 * (10 + 1 + 3 * 0.5));
  EXPECT_DOUBLE_EQ(e.work[1], 4 * (1 + 1 + 3 * 0.5));
}

// What the machine reports, as a listener hears it: the phases in the order the machine goes through them,
// and while tracing a fraction that only grows and ends at 100%.
void expectTheMachinesPhasesAndWork(const std::vector<ProgressSnapshot>& heard, const std::string& label) {
  std::vector<std::string> phases;
  for (const ProgressSnapshot& s : heard)
    if (phases.empty() || phases.back() != s.phase) phases.push_back(s.phase);
  EXPECT_EQ(phases, (std::vector<std::string>{"partitioning", "pruning", "cells", "tracing"})) << label;
  double last = 0;
  std::size_t counts = 0;
  for (const ProgressSnapshot& s : heard) {
    if (s.phase != "tracing") continue;
    ++counts;
    EXPECT_GE(s.fraction, last) << label << ": the fraction went backwards";
    EXPECT_LE(s.fraction, 1.0) << label;
    last = s.fraction;
  }
  EXPECT_GE(counts, 2u) << label << ": the start and the end of tracing at least";
  ASSERT_FALSE(heard.empty());
  EXPECT_EQ(heard.back().phase, "tracing") << label;
  EXPECT_EQ(heard.back().fraction, 1.0) << label;
}

// The machine's progress follows the work of every ray, not the primaries shot (on shells5 those are all
// shot early in the run, and a primary-ray count sat at 95%).
TEST(MachineProgress, ThreadsReportThePhasesAndTheWork) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings m = testing_support::uniformGrid(2, 3, 4, node::LightRayMode::Messages);
  m.balance = Balance::Bsp;
  Progress line(false);
  std::vector<ProgressSnapshot> heard;
  line.listen([&](const ProgressSnapshot& s) { heard.push_back(s); });
  MachineReport report;
  const RenderResult result =
      testing_support::renderMachineWatched(scene, testing_support::settingsFor(64), m, report, "progress");
  expectTheMachinesPhasesAndWork(heard, "threads");
  EXPECT_GT(result.counters.totalRays(), 64u * 64u) << "the scene must have secondary rays to count";
}

TEST(MachineProgress, SimulatedTimeReportsThePhasesAndTheWork) {
  const core::Scene scene = core::makeBalls(2);
  MachineSettings m;
  m.rows = 2;
  m.columns = 2;
  m.emulate = builtinPlatform("ipsc1");
  Progress line(false);
  std::vector<ProgressSnapshot> heard;
  line.listen([&](const ProgressSnapshot& s) { heard.push_back(s); });
  MachineReport report;
  testing_support::renderMachineWatched(scene, testing_support::settingsFor(96), m, report,
                                        "simulated progress");
  expectTheMachinesPhasesAndWork(heard, "simulated");
  const auto counts = std::count_if(heard.begin(), heard.end(), [](const ProgressSnapshot& s) {
    return s.phase == "tracing" && s.fraction > 0 && s.fraction < 1;
  });
  EXPECT_GT(counts, 0) << "the simulation sends its progress along with its contributions";
}

}  // namespace
}  // namespace raycube::host
