// Numerical stability, 2: rays that graze surfaces: the eye in a polygon's plane, eye rays along polygon
// edges and tangent to a sphere, and the contact point of a ball on the floor.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "core/spd/balls.h"
#include "core/view.h"
#include "stability_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;
using core::Color;
using core::Vec3;

class StabilityGrazing : public PrecisionStability {};

// The eye lies in the planes z = 0 and x = 0, each holding a polygon: with an odd image size the centre row
// and column of eye rays lie exactly in those planes (along their edges, through their vertices). A third
// polygon, facing the eye, has its vertices on pixel-centre rays, so whole rows and columns of eye rays
// run exactly along its edges.
core::Scene edgeOnPolygons(int side) {
  const Vec3 eye(0, -5, 0);
  core::Camera camera;
  camera.from = eye;
  camera.at = Vec3(0, 0, 0);
  camera.up = Vec3(0, 0, 1);
  camera.angleDegrees = 40;
  const core::View view(camera, side, side, core::Sampling::Centers);
  auto onWall = [&](int sx, int sy) {
    const core::Ray r = view.eyeRay(sx, sy);
    return r.at((2.0 - eye.y) / r.direction.y);  // the pixel-centre ray where it meets the plane y = 2
  };
  const int lo = side / 4, hi = side - 1 - side / 4;
  SceneBuilder b(camera.from, camera.at, camera.up, camera.angleDegrees);
  b.material(Color(0.9, 0.8, 0.6), 0.7, 0.3)
      .polygon(
          {Vec3(-2, -1, 0), Vec3(2, -1, 0), Vec3(2, 3, 0), Vec3(-2, 3, 0)})  // plane z = 0, holds the eye
      .polygon(
          {Vec3(0, -1, -2), Vec3(0, 3, -2), Vec3(0, 3, 2), Vec3(0, -1, 2)})  // plane x = 0, holds the eye
      .material(Color(0.4, 0.8, 0.5), 0.6, 0.4)
      .polygon({onWall(lo, hi), onWall(hi, hi), onWall(hi, lo), onWall(lo, lo)})  // edges on pixel centres
      .polygon({onWall(hi, hi), onWall(side - 1, hi), onWall(hi, 0)})  // shares a vertex and an edge line
      .material(Color(0.8, 0.3, 0.3), 0.9, 0)
      .sphere(Vec3(0, 8, 0), 4)
      .light(Vec3(3, -3, 4))
      .light(Vec3(-4, -2, 0));  // in the plane z = 0 too
  return b.scene();
}

// A sphere whose silhouette passes exactly through pixel centres: the eye rays through (centre +- k, centre)
// and (centre, centre +- k) are tangent to it (discriminant 0 up to rounding).
// radiusUlps nudges the radius by that many units in the last place, so that across the nudges rounding
// puts the discriminant on both sides of 0 and exactly on it.
core::Scene tangentSphere(int side, bool transparent, int radiusUlps) {
  const double distance = 10;
  core::Camera camera;
  camera.from = Vec3(0, -distance, 0);
  camera.at = Vec3(0, 0, 0);
  camera.up = Vec3(0, 0, 1);
  camera.angleDegrees = 30;
  const core::View view(camera, side, side, core::Sampling::Centers);
  const double u = view.sampleU(side / 2 + side / 3);  // tan of the tangent ray's angle to the axis
  double radius = distance * u / std::sqrt(1 + u * u);
  for (int i = 0; i < std::abs(radiusUlps); ++i)
    radius = std::nextafter(radius, radiusUlps > 0 ? core::kInfinity : 0.0);
  SceneBuilder b(camera.from, camera.at, camera.up, camera.angleDegrees);
  if (transparent)
    b.material(Color(1), 0.1, 0.2, 30, 0.7, 1.5);
  else
    b.material(Color(0.6, 0.7, 0.9), 0.5, 0.5, 30);
  b.sphere(Vec3(0, 0, 0), radius)
      .material(Color(0.9, 0.8, 0.6), 0.8, 0)
      .polygon({Vec3(-50, -50, -2 * radius), Vec3(50, -50, -2 * radius), Vec3(50, 50, -2 * radius),
                Vec3(-50, 50, -2 * radius)})
      .light(Vec3(4, -6, 5))
      .light(Vec3(0, -10, 0));  // at the eye: light rays graze the silhouette too
  return b.scene();
}

// The sphereflake's big ball rests on the floor at (0, 0, -0.5): seen from just above the contact point.
core::Scene contactPoint() {
  core::Scene scene = core::makeBalls(2);
  scene.camera.from = Vec3(0.3, 0.3, -0.45);
  scene.camera.at = Vec3(0, 0, -0.5);
  scene.camera.hither = 0.001;
  return scene;
}

TEST_P(StabilityGrazing, EyeInAPolygonsPlaneAndRaysAlongItsEdges) {
  const int side = sanitized() ? 17 : 33;
  const RenderSettings settings = settingsOf(side, side);
  const core::Scene scene = edgeOnPolygons(side);
  const RenderResult ref = reference(scene, settings, "edge-on polygons");
  expectMachineMatches(scene, settings, machineFor(3, 5), ref, "edge-on polygons 3x5 messages");
  expectMachineMatches(scene, settings, machineFor(3, 5, node::LightRayMode::Pyramid), ref,
                       "edge-on polygons 3x5 pyramid");
}

TEST_P(StabilityGrazing, EyeRaysTangentToASphere) {
  const int side = sanitized() ? 19 : 37;
  const RenderSettings settings = settingsOf(side, side);
  for (bool transparent : {false, true}) {
    for (int ulps : {-2, -1, 0, 1, 2, 4}) {
      const std::string label =
          std::string(transparent ? "tangent transparent sphere" : "tangent mirror sphere") + " radius " +
          std::to_string(ulps) + " ulps";
      const core::Scene scene = tangentSphere(side, transparent, ulps);
      const RenderResult ref = reference(scene, settings, label);
      expectMachineMatches(scene, settings, machineFor(3, 5), ref, label + " 3x5 messages");
      expectMachineMatches(scene, settings, machineFor(3, 5, node::LightRayMode::Pyramid), ref,
                           label + " 3x5 pyramid");
    }
  }
}

TEST_P(StabilityGrazing, BigBallTouchingTheFloor) {
  const int side = sanitized() ? 16 : 40;
  const RenderSettings settings = settingsOf(side, side);
  const core::Scene scene = contactPoint();
  const RenderResult ref = reference(scene, settings, "contact");
  ASSERT_GT(ref.counters.of(core::RayKind::Reflected), 0u);
  expectMachineMatches(scene, settings, machineFor(3, 5), ref, "contact 3x5 messages");
  expectMachineMatches(scene, settings, machineFor(3, 5, node::LightRayMode::Pyramid), ref,
                       "contact 3x5 pyramid");
}

INSTANTIATE_TEST_SUITE_P(Precisions, StabilityGrazing,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);

}  // namespace
}  // namespace raycube::host
