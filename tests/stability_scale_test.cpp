// Numerical stability, 1: scale. Every tolerance is relative (core/tolerances.h), so balls2 in micrometres or
// in thousands of kilometres is the same picture, and the machine's planes, cells and padded boxes still
// agree with brute force.
#include <gtest/gtest.h>

#include "core/spd/balls.h"
#include "stability_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

TEST(StabilityScale, Balls2FromMicroToMegaRendersTheUnitScaleImageOnBothRenderers) {
  const int side = sanitized() ? 16 : 48;
  const RenderSettings settings = settingsOf(side, side);
  const core::Scene base = core::makeBalls(2);
  const RenderResult unit = reference(base, settings, "balls2 x1");
  ASSERT_GT(unit.counters.of(core::RayKind::Reflected), 0u);
  const std::vector<double> factors =
      sanitized() ? std::vector<double>{1e-6, 1e6} : std::vector<double>{1e-6, 1e-3, 1.0, 1e3, 1e6};
  for (double factor : factors) {
    const std::string label = "balls2 x" + testing::PrintToString(factor);
    const core::Scene scene = core::scaledBy(base, factor);
    const RenderResult ref = reference(scene, settings, label);
    const core::ImageDifference diff = core::compareImages(unit.image, ref.image);
    EXPECT_LE(diff.maxAbs, core::kOneSrgbLevel)
        << label << ": reference vs unit scale, " << diff.pixelsOver << " pixels over one sRGB level";
    for (node::LightRayMode mode : {node::LightRayMode::Messages, node::LightRayMode::Pyramid}) {
      const std::string modeLabel = label + " 4x4 " + modeName(mode);
      MachineReport report;
      const RenderResult machine =
          renderMachineWatched(scene, settings, machineFor(4, 4, mode, 8), report, modeLabel);
      EXPECT_EQ(nonFinitePixels(machine.image), 0u) << modeLabel;
      EXPECT_LE(core::compareImages(unit.image, machine.image).maxAbs, core::kOneSrgbLevel)
          << modeLabel << ": machine vs unit scale";
      EXPECT_TRUE(core::bitIdentical(machine.image, ref.image))
          << modeLabel << ": machine vs reference: " << describeDifference(machine.image, ref.image);
    }
    // Conservation and contributions, once per scale.
    expectMachineMatches(scene, settings, machineFor(4, 4), ref, label + " 4x4 conservation");
  }
}

}  // namespace
}  // namespace raycube::host
