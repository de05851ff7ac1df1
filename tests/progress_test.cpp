// Progress that tells the truth: named phases, a fraction of the phase's estimated work (never 100% before
// the end), one progress line per process that renderers join, and a ray estimate close to the real count.
#include "host/progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "core/balls.h"
#include "core/view.h"
#include "core/whitted.h"
#include "host/load_estimate.h"
#include "host/sequential_renderers.h"

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
  progress.setDone(600);
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.6);
  progress.expectWork(2000);
  EXPECT_DOUBLE_EQ(progress.snapshot().fraction, 0.3);
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

}  // namespace
}  // namespace raycube::host
