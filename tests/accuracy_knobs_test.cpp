// Speed against accuracy: the antialiasing and adaptive-depth knobs are honoured by every rendering mode and
// keep the image independent of who traces which ray.
#include <gtest/gtest.h>

#include "core/spd/balls.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

RenderSettings knobs(int side, int spp, double minWeight) {
  RenderSettings s = settingsFor(side);
  s.shading.raysPerSample = spp;
  s.shading.minWeight = minWeight;
  return s;
}

void expectEveryModeMatches(const core::Scene& scene, const RenderSettings& settings,
                            const RenderResult& reference) {
  RenderSettings threads = settings;
  for (int t : {1, 2}) {
    threads.threads = t;
    EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, threads).image, reference.image))
        << t << " threads";
  }
  MachineSettings bsp;
  bsp.rows = 1;
  bsp.columns = 5;
  for (const MachineSettings& m : {uniformGrid(3, 5, 1), uniformGrid(4, 4, 128), bsp}) {
    MachineReport report;
    const RenderResult result = renderMachineWatched(scene, settings, m, report, "knobs");
    EXPECT_TRUE(core::bitIdentical(result.image, reference.image)) << m.rows << "x" << m.columns;
    EXPECT_EQ(result.counters.rays, reference.counters.rays);
  }
}

TEST(Antialiasing, JitteredSamplesAreTheSameWhoeverTracesThem) {
  const core::Scene scene = core::makeBalls(2);
  const int side = sanitized() ? 16 : 32;
  const RenderResult one = renderReference(scene, knobs(side, 1, 0));
  const RenderResult four = renderReference(scene, knobs(side, 4, 0));
  EXPECT_EQ(four.counters.of(core::RayKind::Eye), 4u * side * side);
  const core::ImageDifference d = core::compareImages(one.image, four.image);
  EXPECT_GT(d.rmse, 0);     // the jitter moves the rays
  EXPECT_LT(d.rmse, 0.08);  // but only within each pixel
  expectEveryModeMatches(scene, knobs(side, 4, 0), four);
  // A fixed seed per pixel: the same image every run.
  EXPECT_TRUE(core::bitIdentical(renderReference(scene, knobs(side, 4, 0)).image, four.image));
}

TEST(AdaptiveDepth, CutsReflectedRaysAndKeepsTheImageClose) {
  const core::Scene scene = core::makeBalls(2);
  const int side = sanitized() ? 16 : 32;
  const RenderResult full = renderReference(scene, knobs(side, 1, 0));
  const RenderResult cut = renderReference(scene, knobs(side, 1, 0.3));
  EXPECT_LT(cut.counters.of(core::RayKind::Reflected), full.counters.of(core::RayKind::Reflected));
  EXPECT_LT(core::compareImages(full.image, cut.image).rmse, 0.05);
  expectEveryModeMatches(scene, knobs(side, 1, 0.3), cut);
  // Off by default: min weight 0 spawns every ray (SPD rule 8).
  EXPECT_EQ(renderReference(scene, settingsFor(side)).counters.rays, full.counters.rays);
}

TEST(AdaptiveDepth, WeightIsPerSampleWhateverTheRaysPerSample) {
  const core::Scene scene = core::makeBalls(1);
  const RenderResult one = renderReference(scene, knobs(16, 1, 0.3));
  const RenderResult four = renderReference(scene, knobs(16, 4, 0.3));
  // Each of the four rays carries a quarter of the weight; the cut-off must not treat that as small.
  EXPECT_GT(four.counters.of(core::RayKind::Reflected), 2 * one.counters.of(core::RayKind::Reflected));
}

}  // namespace
}  // namespace raycube::host
