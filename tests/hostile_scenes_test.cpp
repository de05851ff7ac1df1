// Hostile scenes found by differential fuzzing (issue 41): whatever the numbers, no walk loops, no engine
// spins, and every mode draws the reference's image.
#include <gtest/gtest.h>

#include <string>

#include "core/image.h"
#include "core/nff_reader.h"
#include "core/precision.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"
#include "test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

RenderSettings sixteen(core::Precision precision) {
  RenderSettings s;
  s.width = s.height = 16;
  s.progress = false;
  s.precision = precision;
  return s;
}

// Every machine configuration the differential fuzzer runs (tests/fuzz/differential_oracle.cpp).
std::vector<std::pair<std::string, MachineSettings>> machines() {
  MachineSettings bsp;
  bsp.rows = bsp.columns = 2;
  bsp.balance = Balance::Bsp;
  bsp.lightRays = node::LightRayMode::Messages;
  MachineSettings paper = uniformGrid(2, 2, 512);
  paper.cells = node::CellStructure::Paper;
  return {{"2x2 uniform", uniformGrid(2, 2, 512)},
          {"2x2 bsp, light rays as messages", bsp},
          {"2x2 uniform, paper cells", paper}};
}

void expectEveryModeDrawsTheReference(const core::Scene& scene, core::Precision precision) {
  const RenderSettings settings = sixteen(precision);
  const core::Image reference = renderReference(scene, settings).image;
  EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, settings).image, reference)) << "image-parallel";
  for (const auto& [label, machine] : machines()) {
    MachineReport report;
    const RenderResult result = renderMachineWatched(scene, settings, machine, report, label);
    EXPECT_TRUE(core::bitIdentical(result.image, reference)) << label;
  }
}

// Class 1: a sphere of radius 6e7 in float sends light rays of NaN; the float machine's walk asked for the
// ray's next part forever (a NaN tMax ends no part), at 100% CPU. Now every walk is bounded.
TEST(HostileScenes, ALightRayOfNaNEndsInEveryMode) {
  const core::Scene scene = core::parseNff(
      "v\nfrom 1 3 7\nat 0 0 0\nup 0 0 1\nangle 45\nhither 0\nresolution 3 2\nl 1 -4  5\n"
      "f 1 0 3 0 5 7 0 1\ns 0 0 0 5\ns 4 0 .5 60617284",
      "nan_light_ray.nff");
  for (const core::Precision precision : {core::Precision::Float, core::Precision::Double}) {
    SCOPED_TRACE(core::nameOf(precision));
    expectEveryModeDrawsTheReference(scene, precision);
  }
}

}  // namespace
}  // namespace raycube::host
