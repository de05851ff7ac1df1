#pragma once
// Shared by the stability test programs (stability_*_test.cpp): numerical stability at the edges of the input
// space. Everywhere: no NaN or Inf reaches a pixel, and the message-passing machine still renders bit for bit
// what the one-thread reference renders, with every ray it spawns finished (Priol & Bouatouch 3.6).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host::testing_support {

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

// ---- Renders and what every render must satisfy -----------------------------------------------------------

inline RenderSettings settingsOf(int width, int height, int maxDepth = 5,
                                 core::Precision precision = core::Precision::Double) {
  RenderSettings s = settingsFor(width);
  s.height = height;
  s.shading.maxDepth = maxDepth;
  s.precision = precision;
  return s;
}

// The stability suites run in both precisions: float rays must meet the same properties (no NaN, the machine
// equal to the reference bit for bit, every ray finished) as double ones.
class PrecisionStability : public testing::TestWithParam<core::Precision> {
 protected:
  RenderSettings settingsOf(int width, int height, int maxDepth = 5) const {
    return testing_support::settingsOf(width, height, maxDepth, GetParam());
  }
};

inline std::string precisionName(const testing::TestParamInfo<core::Precision>& info) {
  return core::nameOf(info.param);
}

// Light rays travel as messages unless a test says otherwise; small FIFOs, so that they fill.
inline MachineSettings machineFor(int rows, int columns,
                                  node::LightRayMode lightRays = node::LightRayMode::Messages,
                                  std::size_t capacity = 8) {
  return uniformGrid(rows, columns, capacity, lightRays);
}

inline const char* modeName(node::LightRayMode mode) {
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

inline RenderResult reference(const core::Scene& scene, const RenderSettings& settings,
                              const std::string& label) {
  RenderResult result = renderReference(scene, settings);
  EXPECT_EQ(nonFinitePixels(result.image), 0u) << label << ": reference has NaN/Inf pixels";
  EXPECT_EQ(result.counters.nonFinite, 0u) << label << ": reference made NaN/Inf contributions";
  return result;
}

// The machine renders the reference's image bit for bit, spawns and finishes the same rays of every kind
// (conservation: nothing lost, nothing duplicated) and delivers every contribution.
inline void expectMachineMatches(const core::Scene& scene, const RenderSettings& settings,
                                 const MachineSettings& machine, const RenderResult& expected,
                                 const std::string& label) {
  MachineReport report;
  const RenderResult result = renderMachineWatched(scene, settings, machine, report, label);
  EXPECT_EQ(nonFinitePixels(result.image), 0u) << label << ": machine has NaN/Inf pixels";
  expectMachineMatchesReference(expected, result, report, label);
}

inline void expectMachineMatchesInEveryLightMode(const core::Scene& scene, const RenderSettings& settings,
                                                 int rows, int columns, const RenderResult& expected,
                                                 const std::string& label) {
  for (node::LightRayMode mode :
       {node::LightRayMode::Messages, node::LightRayMode::Cone, node::LightRayMode::Pyramid}) {
    expectMachineMatches(
        scene, settings, machineFor(rows, columns, mode, 8), expected,
        label + " " + std::to_string(rows) + "x" + std::to_string(columns) + " " + modeName(mode));
  }
}

}  // namespace raycube::host::testing_support
