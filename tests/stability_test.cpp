// Numerical stability at the edges of the input space: scenes at extreme scales, rays that graze surfaces,
// refraction up to and past the critical angle, geometry and lights exactly on the machine's region
// boundaries, and degenerate depths, image sizes and objects. Everywhere: no NaN or Inf reaches a pixel,
// and the message-passing machine still renders bit for bit what the one-thread reference renders, with
// every ray it spawns finished (Priol & Bouatouch 3.6).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/balls.h"
#include "core/facing_mirrors.h"
#include "core/image.h"
#include "core/intersect.h"
#include "core/nff_reader.h"
#include "core/view.h"
#include "core/whitted.h"
#include "host/machine.h"
#include "host/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;
using core::Color;
using core::Vec3;

// ---- Scenes -----------------------------------------------------------------------------------------------

// A scene built in code, so that positions computed from the view (pixel-centre rays, tangents) keep every
// bit instead of passing through decimal text.
class SceneBuilder {
 public:
  SceneBuilder(Vec3 from, Vec3 at, Vec3 up, double angleDegrees, double hither = 0.001) {
    scene_.name = "stability";
    scene_.background = Color(0.1, 0.2, 0.3);
    scene_.camera.from = from;
    scene_.camera.at = at;
    scene_.camera.up = up;
    scene_.camera.angleDegrees = angleDegrees;
    scene_.camera.hither = hither;
  }
  // An NFF "f" line; the objects that follow use it.
  SceneBuilder& material(Color color, double kd, double ks, double shine = 20, double t = 0, double ior = 1) {
    scene_.materials.push_back(core::Material{color, kd, ks, shine, t, ior});
    return *this;
  }
  SceneBuilder& sphere(Vec3 center, double radius) {
    scene_.objects.push_back(core::Object{core::Sphere{center, radius}, currentMaterial(), false});
    return *this;
  }
  SceneBuilder& polygon(std::vector<Vec3> vertices) {
    scene_.objects.push_back(core::Object{core::Polygon{std::move(vertices)}, currentMaterial(), false});
    return *this;
  }
  SceneBuilder& light(Vec3 position) {
    scene_.lights.push_back(core::Light{position, Color(1), false});
    return *this;
  }
  SceneBuilder& light(Vec3 position, Color color) {
    scene_.lights.push_back(core::Light{position, color, true});
    return *this;
  }
  const core::Scene& scene() const { return scene_; }

 private:
  std::uint32_t currentMaterial() const { return std::uint32_t(scene_.materials.size() - 1); }
  core::Scene scene_;
};

// ---- Renders and what every render must satisfy
// ------------------------------------------------------------

RenderSettings settingsOf(int width, int height, int maxDepth = 5,
                          core::Precision precision = core::Precision::Double) {
  RenderSettings s = settingsFor(1);
  s.width = width;
  s.height = height;
  s.shading.maxDepth = maxDepth;
  s.precision = precision;
  return s;
}

// The suites below run in both precisions: float rays must meet the same properties (no NaN, the machine
// equal to the reference bit for bit, every ray finished) as double ones.
class PrecisionStability : public testing::TestWithParam<core::Precision> {
 protected:
  RenderSettings settingsOf(int width, int height, int maxDepth = 5) const {
    return host::settingsOf(width, height, maxDepth, GetParam());
  }
};
class StabilityGrazing : public PrecisionStability {};
class StabilityRefraction : public PrecisionStability {};
class StabilityRegions : public PrecisionStability {};
class StabilityDegenerate : public PrecisionStability {};

std::string precisionName(const testing::TestParamInfo<core::Precision>& info) {
  return core::nameOf(info.param);
}

MachineSettings machineFor(int rows, int columns, node::LightRayMode lightRays = node::LightRayMode::Messages,
                           std::size_t capacity = 8) {
  MachineSettings m;
  m.rows = rows;
  m.columns = columns;
  m.balance = Balance::Uniform;
  m.queueCapacity = capacity;
  m.lightRays = lightRays;
  return m;
}

const char* modeName(node::LightRayMode mode) {
  switch (mode) {
    case node::LightRayMode::Messages:
      return "messages";
    case node::LightRayMode::Cone:
      return "cone";
    case node::LightRayMode::Pyramid:
      return "pyramid";
  }
  return "?";
}

std::size_t nonFinitePixels(const core::Image& image) {
  std::size_t count = 0;
  for (const Color& c : image.pixels)
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) ++count;
  return count;
}

RenderResult reference(const core::Scene& scene, const RenderSettings& settings, const std::string& label) {
  RenderResult result = renderReference(scene, settings);
  EXPECT_EQ(nonFinitePixels(result.image), 0u) << label << ": reference has NaN/Inf pixels";
  EXPECT_EQ(result.counters.nonFinite, 0u) << label << ": reference made NaN/Inf contributions";
  return result;
}

// The machine renders the reference's image bit for bit, spawns and finishes the same rays of every kind
// (conservation: nothing lost, nothing duplicated) and delivers every contribution.
void expectMachineMatches(const core::Scene& scene, const RenderSettings& settings,
                          const MachineSettings& machine, const RenderResult& expected,
                          const std::string& label) {
  MachineReport report;
  const RenderResult result = renderMachineWatched(scene, settings, machine, report, label);
  EXPECT_EQ(nonFinitePixels(result.image), 0u) << label << ": machine has NaN/Inf pixels";
  expectMachineMatchesReference(expected, result, report, label);
}

void expectMachineMatchesInEveryLightMode(const core::Scene& scene, const RenderSettings& settings, int rows,
                                          int columns, const RenderResult& expected,
                                          const std::string& label) {
  for (node::LightRayMode mode :
       {node::LightRayMode::Messages, node::LightRayMode::Cone, node::LightRayMode::Pyramid}) {
    expectMachineMatches(
        scene, settings, machineFor(rows, columns, mode, 8), expected,
        label + " " + std::to_string(rows) + "x" + std::to_string(columns) + " " + modeName(mode));
  }
}

// ---- 1. Scale
// ---------------------------------------------------------------------------------------------- Every
// tolerance is relative (core/tolerances.h), so balls2 in micrometres or in thousands of kilometres is the
// same picture, and the machine's planes, cells and padded boxes still agree with brute force.

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

// ---- 2. Grazing rays
// ----------------------------------------------------------------------------------------

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
      .light(Vec3(0, -10, 0));  // at the eye: shadow rays graze the silhouette too
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

// ---- 3. Refraction
// ------------------------------------------------------------------------------------------

// A diffuse sphere on a floor, and (optionally) glass in front of it: T = 1, Kd = Ks = 0.
core::Scene glassInFront(bool withGlass, double ior) {
  SceneBuilder b(Vec3(0, -6, 1), Vec3(0, 0, 0.6), Vec3(0, 0, 1), 40);
  b.material(Color(0.9, 0.8, 0.6), 0.8, 0)
      .polygon({Vec3(-8, -8, 0), Vec3(8, -8, 0), Vec3(8, 8, 0), Vec3(-8, 8, 0)})
      .material(Color(0.8, 0.3, 0.3), 0.9, 0)
      .sphere(Vec3(0, 1.5, 1), 1)
      .light(Vec3(4, -4, 6))
      .light(Vec3(-3, -5, 3));
  if (withGlass) b.material(Color(1), 0, 0, 0, 1, ior).sphere(Vec3(0.3, -1.5, 0.8), 0.7);
  return b.scene();
}

// Two overlapping glass spheres (T = 1, Ks = 0) before a diffuse sphere and floor. Inside the lens where
// they overlap a ray meets the far surface of one sphere at an angle unrelated to the one it entered by, so
// at high indices it is totally reflected; with Ks = 0 everywhere that is the only source of reflected rays.
core::Scene overlappingGlass(double ior) {
  SceneBuilder b(Vec3(0, -6, 1), Vec3(0, 0, 0.8), Vec3(0, 0, 1), 40);
  b.material(Color(0.9, 0.8, 0.6), 0.8, 0)
      .polygon({Vec3(-8, -8, 0), Vec3(8, -8, 0), Vec3(8, 8, 0), Vec3(-8, 8, 0)})
      .material(Color(0.8, 0.3, 0.3), 0.9, 0)
      .sphere(Vec3(0, 2, 1.2), 1)
      .material(Color(1), 0, 0, 0, 1, ior)
      .sphere(Vec3(-0.4, -1, 1), 0.8)
      .sphere(Vec3(0.4, -1.2, 1.1), 0.8)
      .light(Vec3(4, -4, 6))
      .light(Vec3(-3, -5, 3));
  return b.scene();
}

TEST_P(StabilityRefraction, GlassWithTheIndexOfAirIsInvisible) {
  const int side = sanitized() ? 16 : 32;
  RenderSettings settings = settingsOf(side, side, 8);
  const RenderResult without = reference(glassInFront(false, 1.0), settings, "no glass");
  const RenderResult air = reference(glassInFront(true, 1.0), settings, "glass of index 1");
  ASSERT_GT(air.counters.of(core::RayKind::Refracted), 0u) << "the glass sphere is not in view";
  const core::ImageDifference diff = core::compareImages(without.image, air.image);
  EXPECT_LE(diff.maxAbs, core::kOneSrgbLevel) << diff.pixelsOver << " pixels over one sRGB level";
  // The comparison has teeth: real glass in the same place is visible.
  const RenderResult glass = reference(glassInFront(true, 1.5), settings, "glass of index 1.5");
  EXPECT_GT(core::compareImages(without.image, glass.image).pixelsOver, 0u);
}

TEST_P(StabilityRefraction, HighIndicesRefractAndTotallyReflectWithoutNaN) {
  const int side = sanitized() ? 16 : 32;
  const RenderSettings settings = settingsOf(side, side, 8);
  const RenderResult air = reference(overlappingGlass(1.0), settings, "overlapping glass ior 1");
  EXPECT_EQ(air.counters.of(core::RayKind::Reflected), 0u) << "reflected rays without Ks or total reflection";
  for (double ior : {1.5, 2.4}) {
    const std::string label = "overlapping glass ior " + testing::PrintToString(ior);
    const core::Scene scene = overlappingGlass(ior);
    const RenderResult ref = reference(scene, settings, label);
    EXPECT_GT(ref.counters.of(core::RayKind::Refracted), 0u) << label;
    if (ior == 2.4) {
      EXPECT_GT(ref.counters.of(core::RayKind::Reflected), 0u) << label << ": no total reflection";
    }
    expectMachineMatches(scene, settings, machineFor(4, 4), ref, label + " 4x4 messages");
    expectMachineMatches(scene, settings, machineFor(3, 5, node::LightRayMode::Pyramid), ref,
                         label + " 3x5 pyramid");
  }
}

// A ray inside a glass sphere meets the surface at the critical angle asin(1 / ior), and a hair either side
// of it. Whichever side of Snell's test rounding puts it, the transmitted share T is carried on: by a
// refracted ray, or by the reflected ray on total internal reflection (core/whitted.cpp), never both, never
// neither, and never as NaN.
TEST_P(StabilityRefraction, CriticalAngleFromInsideKeepsTheTransmittedShare) {
  for (double ks : {0.0, 0.25}) {
    for (double ior : {1.33, 1.5, 2.4}) {
      core::Scene scene;
      scene.lights.push_back(core::Light{Vec3(0, 0, 5), Color(1), false});
      scene.materials.push_back(core::Material{Color(1), 0.2, ks, 10, 1.0, ior});
      scene.objects.push_back(core::Object{core::Sphere{Vec3(0, 0, 0), 1}, 0, false});
      const core::Whitted whitted(scene, core::ShadingOptions{});
      bool sawRefraction = false, sawTotalReflection = false;
      for (double nudge : {-1e-9, -1e-12, -1e-15, 0.0, 1e-15, 1e-12, 1e-9}) {
        const std::string label = "ior " + testing::PrintToString(ior) + " Ks " + testing::PrintToString(ks) +
                                  " nudge " + testing::PrintToString(nudge);
        const double angle = std::asin(1 / ior) + nudge;
        core::TracedRay ray;
        ray.ray.direction = Vec3(std::sin(angle), 0, std::cos(angle));
        // From the middle of the chord that ends at the pole (0, 0, 1), where the normal is +z.
        ray.ray.origin = Vec3(0, 0, 1) - std::cos(angle) * ray.ray.direction;
        ray.ray.tMin = 0;
        ray.ray.tMax = core::kInfinity;
        ray.coeff = 0.7;
        ray.depth = 2;
        ray.kind = core::RayKind::Refracted;
        const double t = core::nearestHit(scene.objects[0], ray.ray, core::kInfinity);
        ASSERT_TRUE(std::isfinite(t)) << label;
        ASSERT_NEAR(t, std::cos(angle), 1e-12) << label;
        core::RayOutcome out;
        whitted.shadeHit(ray, core::Hit{t, 0}, out);
        double carried = 0;
        int refracted = 0, reflected = 0;
        for (const core::TracedRay& s : out.spawned) {
          EXPECT_TRUE(std::isfinite(s.ray.origin.x) && std::isfinite(s.ray.origin.y) &&
                      std::isfinite(s.ray.origin.z))
              << label;
          EXPECT_NEAR(glm::length(s.ray.direction), 1.0, 1e-12) << label << " kind " << int(s.kind);
          EXPECT_TRUE(std::isfinite(s.coeff)) << label;
          if (s.kind == core::RayKind::Refracted) {
            ++refracted;
            carried += s.coeff;
            // It leaves the sphere, at most grazing the surface.
            EXPECT_GE(glm::dot(s.ray.direction, Vec3(0, 0, 1)), -1e-12) << label;
          } else if (s.kind == core::RayKind::Reflected) {
            ++reflected;
            carried += s.coeff;
            EXPECT_LE(s.ray.direction.z, 0.0) << label << ": reflected ray leaves the sphere";
          }
        }
        for (const core::Contribution& c : out.contributions)
          EXPECT_TRUE(std::isfinite(c.value.x) && std::isfinite(c.value.y) && std::isfinite(c.value.z))
              << label;
        EXPECT_NEAR(carried, ray.coeff * (ks + 1.0), 1e-12) << label;
        EXPECT_LE(refracted, 1) << label;
        EXPECT_EQ(reflected, refracted == 1 ? (ks > 0 ? 1 : 0) : 1) << label;
        sawRefraction = sawRefraction || refracted == 1;
        sawTotalReflection = sawTotalReflection || refracted == 0;
      }
      // The nudges straddle the critical angle, so both branches ran.
      EXPECT_TRUE(sawRefraction) << "ior " << ior;
      EXPECT_TRUE(sawTotalReflection) << "ior " << ior;
    }
  }
}

// ---- 4. Region boundaries
// ----------------------------------------------------------------------------------- With an even image on a
// 2x2 (or 4x4) grid the central region boundaries are the planes u = 0 and v = 0 through the eye: here x = 0
// and z = 0.

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

// ---- 5. Degenerate inputs ---------------------------------------------------------------------------------

TEST_P(StabilityDegenerate, DepthOneShootsOnlyEyeAndShadowRays) {
  const int side = sanitized() ? 16 : 24;
  const RenderSettings settings = settingsOf(side, side, 1);
  const core::Scene scene = core::makeBalls(2);
  const RenderResult ref = reference(scene, settings, "balls2 depth 1");
  EXPECT_EQ(ref.counters.of(core::RayKind::Reflected), 0u);
  EXPECT_GT(ref.counters.of(core::RayKind::Shadow), 0u);
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

TEST_P(StabilityDegenerate, ZeroRadiusAndZeroAreaAreRejected) {
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
  try {
    core::parseNff(header + "p 3\n1 1 1\n1 1 1\n1 1 1\n", "zero_area.nff");
    ADD_FAILURE() << "a polygon of area 0 was accepted";
  } catch (const core::SceneError& e) {
    EXPECT_EQ(e.line(), 10) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, StabilityGrazing,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);
INSTANTIATE_TEST_SUITE_P(Precisions, StabilityRefraction,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);
INSTANTIATE_TEST_SUITE_P(Precisions, StabilityRegions,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);
INSTANTIATE_TEST_SUITE_P(Precisions, StabilityDegenerate,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);

}  // namespace
}  // namespace raycube::host
