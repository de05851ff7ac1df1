// Numerical stability, 4: geometry and lights exactly on the machine's region boundaries, the eye inside a
// sphere, and objects straddling the eye plane. With an even image on a 2x2 (or 4x4) grid the central region
// boundaries are the planes u = 0 and v = 0 through the eye: here x = 0 and z = 0.
#include <gtest/gtest.h>

#include <string>

#include "core/view.h"
#include "stability_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;
using core::Color;
using core::Vec3;

class StabilityRegions : public PrecisionStability {};

core::Scene onTheBoundaries() {
  SceneBuilder b(Vec3(0, -5, 0), Vec3(0, 0, 0), Vec3(0, 0, 1), 50);
  b.material(Color(0.9, 0.8, 0.6), 0.7, 0.3)
      // A wall whose left edge projects onto the centre column boundary, its bottom edge onto the centre row
      // boundary, and its corner onto the point where four regions meet.
      .polygon({Vec3(0, 3, 0), Vec3(3, 3, 0), Vec3(3, 3, 3), Vec3(0, 3, 3)})
      // Polygons lying in the boundary planes themselves (seen edge-on).
      .polygon({Vec3(0, 1, -3), Vec3(0, 4, -3), Vec3(0, 4, -1), Vec3(0, 1, -1)})
      .polygon({Vec3(-3, 1, 0), Vec3(-1, 1, 0), Vec3(-1, 4, 0), Vec3(-3, 4, 0)})
      .material(Color(0.6, 0.6, 0.9), 0.3, 0.6)
      .polygon({Vec3(-20, -20, -2), Vec3(20, -20, -2), Vec3(20, 20, -2), Vec3(-20, 20, -2)})  // mirror floor
      .sphere(Vec3(-1.5, 3, 1.5), 1)
      .sphere(Vec3(0, 2, -1.2), 0.6)  // centred on the column boundary
      .light(Vec3(0, 1, 4))           // on the plane through the eye and the screen's centre column
      .light(Vec3(3, -4, 0))          // on the plane through the eye and the screen's centre row
      .light(Vec3(0, 1.5, 0));        // on both: on the central axis of sight
  return b.scene();
}

TEST_P(StabilityRegions, GeometryAndLightsOnTheCentralBoundaries) {
  const int side = sanitized() ? 16 : 48;
  const RenderSettings settings = settingsOf(side, side);
  const core::View view(onTheBoundaries().camera, side, side, core::Sampling::Centers);
  ASSERT_EQ(view.boundaryU(side / 2), 0.0);
  ASSERT_EQ(view.boundaryV(side / 2), 0.0);
  const core::Scene scene = onTheBoundaries();
  const RenderResult ref = reference(scene, settings, "on the boundaries");
  expectMachineMatchesInEveryLightMode(scene, settings, 2, 2, ref, "on the boundaries");
  expectMachineMatchesInEveryLightMode(scene, settings, 4, 4, ref, "on the boundaries");
  // The same with random delays around every transport operation: another interleaving of the messages.
  MachineSettings jittered = machineFor(2, 2, node::LightRayMode::Messages, 1);
  jittered.jitterSeed = 7;
  expectMachineMatches(scene, settings, jittered, ref, "on the boundaries 2x2 messages capacity 1 jittered");
}

// The eye inside a sphere: every eye ray starts inside it, and the sphere reaches behind the eye plane.
core::Scene eyeInsideSphere(bool transparent) {
  SceneBuilder b(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), 60);
  if (transparent)
    b.material(Color(0.9, 0.95, 1), 0.1, 0.1, 30, 0.8, 1.3);
  else
    b.material(Color(0.7, 0.7, 0.8), 0.7, 0.3, 30);
  b.sphere(Vec3(0.3, 0.2, 0.1), 3)
      .material(Color(0.8, 0.3, 0.3), 0.8, 0.2)
      .sphere(Vec3(0, 1.5, 0), 0.5)
      .sphere(Vec3(0, 6, 0), 1.5)  // outside
      .material(Color(0.9, 0.8, 0.6), 0.8, 0)
      .polygon({Vec3(-20, -20, -4), Vec3(20, -20, -4), Vec3(20, 20, -4), Vec3(-20, 20, -4)})
      .light(Vec3(1, 1, 1))   // inside
      .light(Vec3(5, 5, 5));  // outside
  return b.scene();
}

TEST_P(StabilityRegions, EyeInsideAnOpaqueOrTransparentSphere) {
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsOf(side, side);
  for (bool transparent : {false, true}) {
    const std::string label = transparent ? "eye inside glass" : "eye inside opaque sphere";
    const core::Scene scene = eyeInsideSphere(transparent);
    const RenderResult ref = reference(scene, settings, label);
    if (transparent) {
      EXPECT_GT(ref.counters.of(core::RayKind::Refracted), 0u) << label;
    }
    expectMachineMatchesInEveryLightMode(scene, settings, 2, 2, ref, label);
    expectMachineMatches(scene, settings, machineFor(3, 5), ref, label + " 3x5 messages");
  }
}

// A sphere and a floor cut by the eye plane, a sphere wholly behind the eye, and a mirror that shows them.
core::Scene straddlingTheEyePlane() {
  SceneBuilder b(Vec3(0, -5, 0), Vec3(0, 0, 0), Vec3(0, 0, 1), 60);
  b.material(Color(0.9, 0.8, 0.6), 0.8, 0)
      .polygon({Vec3(-10, -15, -1), Vec3(10, -15, -1), Vec3(10, 5, -1), Vec3(-10, 5, -1)})
      .material(Color(0.3, 0.8, 0.3), 0.7, 0.3)
      .sphere(Vec3(3, -5, 0), 2.5)  // centre on the eye plane
      .sphere(Vec3(0, -8, 0.5), 1)  // behind the eye
      .material(Color(0.9, 0.9, 0.9), 0.2, 0.8)
      .sphere(Vec3(-0.5, 0, 0), 1.2)  // the mirror
      .light(Vec3(2, -8, 4))
      .light(Vec3(-3, 2, 3));
  return b.scene();
}

TEST_P(StabilityRegions, ObjectsStraddlingTheEyePlane) {
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsOf(side, side);
  const core::Scene scene = straddlingTheEyePlane();
  const RenderResult ref = reference(scene, settings, "straddling");
  ASSERT_GT(ref.counters.of(core::RayKind::Reflected), 0u);
  expectMachineMatchesInEveryLightMode(scene, settings, 2, 2, ref, "straddling");
  expectMachineMatches(scene, settings, machineFor(3, 5), ref, "straddling 3x5 messages");
}

INSTANTIATE_TEST_SUITE_P(Precisions, StabilityRegions,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);

}  // namespace
}  // namespace raycube::host
