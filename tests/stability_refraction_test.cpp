// Numerical stability, 3: refraction up to and past the critical angle: glass of the index of air, high
// indices, total internal reflection.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/intersect.h"
#include "core/whitted.h"
#include "stability_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;
using core::Color;
using core::Vec3;

class StabilityRefraction : public PrecisionStability {};

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

INSTANTIATE_TEST_SUITE_P(Precisions, StabilityRefraction,
                         testing::Values(core::Precision::Double, core::Precision::Float), precisionName);

}  // namespace
}  // namespace raycube::host
