// SPD gears 4 (concave 144-vertex gear faces, tested by their banded outlines) renders bit-identically in
// every mode: reference, image-parallel and the machine (its BSP default and a uniform grid), in double and
// float, at a small resolution. A polygon test that depended on the renderer (a BVH's order, a region's
// clipping, a ray's travel) would show here.
#include <gtest/gtest.h>

#include <string>

#include "core/image.h"
#include "core/nff_reader.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

TEST(ConcavePolygonRender, Gears4IsTheSameInEveryModeAndPrecision) {
  const core::Scene scene = core::readNff(scenePath("gears4.nff"));
  for (core::Precision precision : {core::Precision::Double, core::Precision::Float}) {
    RenderSettings settings = settingsFor(sanitized() ? 12 : 24);
    settings.precision = precision;
    const std::string name = std::string("gears4 ") + core::nameOf(precision);
    const RenderResult reference = renderReference(scene, settings);
    EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, settings).image, reference.image))
        << name << ": image-parallel";
    renderAndCompare(scene, reference, settings, MachineSettings{}, name + " machine 4x4 (defaults)");
    renderAndCompare(scene, reference, settings, uniformGrid(3, 5, 8),
                     name + " machine 3x5 uniform, capacity 8");
  }
}

}  // namespace
}  // namespace raycube::host
