// Numerical stability, 5: degenerate inputs: depth 1 and 64, one-pixel images, more processors than pixel
// rows, coincident spheres, a light shut inside a sphere, zero-radius and zero-area objects.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "core/spd/facing_mirrors.h"
#include "stability_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;
using core::Color;
using core::Vec3;

class StabilityDegenerate : public PrecisionStability {};

TEST_P(StabilityDegenerate, DepthOneShootsOnlyEyeAndLightRays) {
  const int side = sanitized() ? 16 : 24;
  const RenderSettings settings = settingsOf(side, side, 1);
  const core::Scene scene = core::makeBalls(2);
  const RenderResult ref = reference(scene, settings, "balls2 depth 1");
  EXPECT_EQ(ref.counters.of(core::RayKind::Reflected), 0u);
  EXPECT_GT(ref.counters.of(core::RayKind::Light), 0u);
  expectMachineMatches(scene, settings, machineFor(2, 2), ref, "balls2 depth 1 2x2");
}

// Two facing mirrors z = -1 and z = 1 with the eye between them: a ray that is not parallel to them bounces
// until the depth limit. With Ks = 1 nothing decays; with Ks = 1e-5 the 64th bounce's coefficient is
// 1e-315, deep in the subnormals: it must underflow towards 0, never become NaN or Inf.

TEST_P(StabilityDegenerate, SixtyFourBouncesBetweenFacingMirrors) {
  const int side = 16;
  for (double ks : {1.0, 0.999, 1e-5}) {
    const std::string label = "mirrors Ks " + testing::PrintToString(ks);
    const core::Scene scene = core::makeFacingMirrors(ks);
    const RenderResult deep = reference(scene, settingsOf(side, side, 64), label + " depth 64");
    const RenderResult shallower = reference(scene, settingsOf(side, side, 63), label + " depth 63");
    // The 64th level exists: one more level adds reflected rays.
    EXPECT_GT(deep.counters.of(core::RayKind::Reflected), shallower.counters.of(core::RayKind::Reflected))
        << label;
    for (const Color& c : deep.image.pixels) EXPECT_GE(std::min({c.x, c.y, c.z}), 0.0) << label;
    expectMachineMatches(scene, settingsOf(side, side, 64), machineFor(2, 2), deep, label + " depth 64 2x2");
  }
}

TEST_P(StabilityDegenerate, OnePixelAndOnePixelWideImages) {
  const core::Scene scene = core::makeBalls(2);
  const int length = sanitized() ? 512 : 4096;
  for (auto [width, height] : std::vector<std::pair<int, int>>{{1, 1}, {1, length}, {length, 1}}) {
    const std::string label = "balls2 " + std::to_string(width) + "x" + std::to_string(height);
    const RenderSettings settings = settingsOf(width, height);
    const RenderResult ref = reference(scene, settings, label);
    ASSERT_EQ(ref.image.width, width);
    ASSERT_EQ(ref.image.height, height);
    EXPECT_EQ(ref.counters.of(core::RayKind::Eye), std::uint64_t(width) * height) << label;
    expectMachineMatches(scene, settings, machineFor(1, 1), ref, label + " 1x1");
  }
}

TEST_P(StabilityDegenerate, MoreUniformProcessorsThanPixelRowsOrColumnsIsRejected) {
  const core::Scene scene = core::makeBalls(1);
  const RenderSettings settings = settingsOf(8, 8);
  EXPECT_THROW(renderMachine(scene, settings, machineFor(9, 1)), std::invalid_argument);
  EXPECT_THROW(renderMachine(scene, settings, machineFor(1, 9)), std::invalid_argument);
  EXPECT_THROW(renderMachine(scene, settingsOf(16, 4), machineFor(5, 2)), std::invalid_argument);
  // The limit is exact: one row per processor is enough.
  MachineReport report;
  EXPECT_NO_THROW(renderMachineWatched(scene, settings, machineFor(8, 1), report, "8 rows of 8"));
}

// Two identical spheres of different colours: the tie rule (equal t, smaller object index) shows only the
// first, everywhere, on every renderer.
TEST_P(StabilityDegenerate, CoincidentSpheresShowTheFirstOnly) {
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsOf(side, side);
  auto scene = [](bool twice) {
    SceneBuilder b(Vec3(0, -6, 1.5), Vec3(0, 0, 0.5), Vec3(0, 0, 1), 40);
    b.material(Color(0.9, 0.8, 0.6), 0.6, 0.3)
        .polygon({Vec3(-8, -8, 0), Vec3(8, -8, 0), Vec3(8, 8, 0), Vec3(-8, 8, 0)})
        .material(Color(0.9, 0.2, 0.2), 0.6, 0.4)
        .sphere(Vec3(0.2, 0, 1), 1);
    if (twice) b.material(Color(0.2, 0.9, 0.2), 0.6, 0.4).sphere(Vec3(0.2, 0, 1), 1);
    return b.light(Vec3(4, -4, 6)).light(Vec3(-3, -5, 3)).scene();
  };
  const core::Scene both = scene(true);
  const RenderResult ref = reference(both, settings, "coincident");
  const RenderResult single = reference(scene(false), settings, "single");
  EXPECT_TRUE(core::bitIdentical(ref.image, single.image)) << describeDifference(ref.image, single.image);
  expectMachineMatches(both, settings, machineFor(2, 2), ref, "coincident 2x2 messages");
  expectMachineMatches(both, settings, machineFor(3, 5, node::LightRayMode::Pyramid), ref,
                       "coincident 3x5 pyramid");
}

// A second light shut inside an opaque sphere lights nothing outside: the picture is exactly the one with
// that light switched off (same light count, so the same ambient and the same intensity for the first).
core::Scene lampInABox(bool enclosed, Color lampColor) {
  SceneBuilder b(Vec3(0, -6, 2), Vec3(0, 0, 0.5), Vec3(0, 0, 1), 45);
  b.material(Color(0.9, 0.8, 0.6), 0.8, 0)
      .polygon({Vec3(-8, -8, 0), Vec3(8, -8, 0), Vec3(8, 8, 0), Vec3(-8, 8, 0)})
      .material(Color(0.5, 0.6, 0.9), 0.7, 0.3)
      .sphere(Vec3(-1.5, 0.5, 0.7), 0.7);
  if (enclosed) b.material(Color(0.8, 0.4, 0.2), 0.8, 0.2).sphere(Vec3(1, 0, 1), 0.6);
  return b.light(Vec3(4, -4, 6), Color(0.7)).light(Vec3(1, 0, 1), lampColor).scene();
}

TEST_P(StabilityDegenerate, LightInsideAnOpaqueSphereLightsNothingOutside) {
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsOf(side, side);
  const core::Scene lit = lampInABox(true, Color(1));
  const RenderResult enclosed = reference(lit, settings, "lamp enclosed");
  const RenderResult off = reference(lampInABox(true, Color(0)), settings, "lamp off");
  EXPECT_TRUE(core::bitIdentical(enclosed.image, off.image)) << describeDifference(enclosed.image, off.image);
  // Teeth: without its sphere the lamp does light the scene.
  const RenderResult open = reference(lampInABox(false, Color(1)), settings, "lamp open");
  const RenderResult openOff = reference(lampInABox(false, Color(0)), settings, "lamp open, off");
  EXPECT_GT(core::compareImages(open.image, openOff.image).pixelsOver, 0u);
  expectMachineMatchesInEveryLightMode(lit, settings, 2, 2, enclosed, "lamp enclosed");
}

// A zero radius is an error; a polygon of zero area is skipped with a warning before any renderer sees it
// (real meshes carry them), and refused when read strictly.
TEST_P(StabilityDegenerate, ZeroRadiusIsRejectedAndZeroAreaNeverRendered) {
  const std::string header =
      "v\nfrom 0 -5 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0.01\nresolution 16 16\n"
      "l 1 -3 4\nf 1 0.5 0.5 0.8 0 0 0 0\n";  // 9 lines
  // The same lines with sound values parse, so the errors below come from the degenerate value alone.
  EXPECT_NO_THROW(core::parseNff(header + "s 0 0 0 1\n", "sound.nff"));
  EXPECT_NO_THROW(core::parseNff(header + "p 3\n0 0 0\n1 0 0\n0 0 1\n", "sound.nff"));
  try {
    core::parseNff(header + "s 0 0 0 0\n", "zero_radius.nff");
    ADD_FAILURE() << "a sphere of radius 0 was accepted";
  } catch (const core::SceneError& e) {
    EXPECT_EQ(e.line(), 10) << e.what();
  }
  const std::string zeroArea = header + "p 3\n1 1 1\n1 1 1\n1 1 1\n";
  const core::Scene skipped = core::parseNff(zeroArea, "zero_area.nff");
  EXPECT_TRUE(skipped.objects.empty());
  ASSERT_EQ(skipped.warnings.size(), 1u);
  EXPECT_NE(skipped.warnings[0].find("zero_area.nff:10"), std::string::npos) << skipped.warnings[0];
  try {
    core::parseNff(zeroArea, "zero_area.nff", core::NffOptions{.strict = true});
    ADD_FAILURE() << "a polygon of area 0 was accepted by a strict read";
  } catch (const core::SceneError& e) {
    EXPECT_EQ(e.line(), 10) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, StabilityDegenerate,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);

}  // namespace
}  // namespace raycube::host
