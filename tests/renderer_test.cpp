// The two yardsticks (host/render/sequential_renderers.h) agree bit for bit, on every shipped scene, whatever
// the thread count and run after run: the promise the fixed-point frame buffer makes
// (host/render/framebuffer.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

int imageSide() {
  return sanitized() ? 16 : 48;
}

// "" stands for the built-in balls scene of size 2; anything else is a file in scenes/.
std::vector<std::string> sceneNames() {
  std::vector<std::string> names{""};
  for (const auto& entry : std::filesystem::directory_iterator(testing_support::sourcePath("scenes")))
    if (entry.path().extension() == ".nff") names.push_back(entry.path().filename().string());
  std::sort(names.begin() + 1, names.end());
  return names;
}

core::Scene loadScene(const std::string& name) {
  if (name.empty()) return core::makeBalls(2);
  return core::readNff(testing_support::scenePath(name));
}

void expectSameRayCounts(const core::TraceCounters& a, const core::TraceCounters& b,
                         const std::string& what) {
  for (int k = 0; k < core::kRayKinds; ++k)
    EXPECT_EQ(a.rays[k], b.rays[k]) << what << ": " << core::rayKindName(core::RayKind(k)) << " rays";
}

struct SceneAndSampling {
  std::string scene;
  core::Sampling sampling;
};

void PrintTo(const SceneAndSampling& c, std::ostream* os) {
  *os << (c.scene.empty() ? "makeBalls(2)" : c.scene)
      << (c.sampling == core::Sampling::Centers ? ", centers" : ", corners");
}

std::vector<SceneAndSampling> allCases() {
  std::vector<SceneAndSampling> cases;
  for (const std::string& name : sceneNames())
    for (core::Sampling s : {core::Sampling::Centers, core::Sampling::Corners}) cases.push_back({name, s});
  return cases;
}

std::string caseName(const testing::TestParamInfo<SceneAndSampling>& info) {
  std::string name = info.param.scene.empty() ? "generated_balls2" : info.param.scene;
  name = name.substr(0, name.find('.'));
  return name + (info.param.sampling == core::Sampling::Centers ? "_centers" : "_corners");
}

class RenderersAgree : public testing::TestWithParam<SceneAndSampling> {};

TEST_P(RenderersAgree, BitIdenticalAcrossRenderersThreadsAndRuns) {
  const core::Scene scene = loadScene(GetParam().scene);
  const int side = imageSide();
  const core::Sampling sampling = GetParam().sampling;

  const RenderResult reference = renderReference(scene, settingsFor(side, sampling));
  ASSERT_EQ(reference.image.width, side);
  ASSERT_EQ(reference.image.height, side);
  EXPECT_EQ(firstNonFinitePixel(reference.image), -1);
  EXPECT_EQ(reference.counters.nonFinite, 0u);

  // Every eye ray is traced once: W x H through centres, (W+1) x (H+1) through corners (SPD rule 6).
  const std::uint64_t eyeRays =
      sampling == core::Sampling::Corners ? std::uint64_t(side + 1) * (side + 1) : std::uint64_t(side) * side;
  EXPECT_EQ(reference.counters.of(core::RayKind::Eye), eyeRays);
  // A scene that is not empty must produce more than eye rays, or the comparison below proves little.
  EXPECT_GT(reference.counters.of(core::RayKind::Light), 0u);

  for (int run = 0; run < 2; ++run) {
    for (int threads : {1, 2, 5}) {
      const std::string what =
          "image-parallel, " + std::to_string(threads) + " threads, run " + std::to_string(run + 1);
      const RenderResult parallel = renderImageParallel(scene, settingsFor(side, sampling, threads));
      EXPECT_TRUE(core::bitIdentical(reference.image, parallel.image))
          << what << ": " << core::countPixelsOver(reference.image, parallel.image, 0.0)
          << " pixels differ from the reference, max abs difference "
          << core::compareImages(reference.image, parallel.image).maxAbs;
      EXPECT_EQ(firstNonFinitePixel(parallel.image), -1) << what;
      EXPECT_EQ(parallel.counters.nonFinite, 0u) << what;
      // Ray counts are a property of the image; intersection and box tests belong to the database query.
      expectSameRayCounts(reference.counters, parallel.counters, what);
      EXPECT_EQ(reference.counters.contributions, parallel.counters.contributions) << what;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryScene, RenderersAgree, testing::ValuesIn(allCases()), caseName);

TEST(RendererCounters, DepthOneSpawnsNoSecondaryRays) {
  const core::Scene scene = core::makeBalls(2);
  RenderSettings settings = settingsFor(imageSide(), core::Sampling::Centers);
  settings.shading.maxDepth = 1;
  for (const RenderResult& r : {renderReference(scene, settings), renderImageParallel(scene, settings)}) {
    EXPECT_EQ(r.counters.of(core::RayKind::Reflected), 0u) << r.mode;
    EXPECT_EQ(r.counters.of(core::RayKind::Refracted), 0u) << r.mode;
    EXPECT_GT(r.counters.of(core::RayKind::Light), 0u) << r.mode;  // depth limits the tree, not the lights
  }
  // And the limit matters: the mirrored balls look different with their reflections.
  settings.shading.maxDepth = 5;
  const RenderResult deep = renderReference(scene, settings);
  EXPECT_GT(deep.counters.of(core::RayKind::Reflected), 0u);
  settings.shading.maxDepth = 1;
  EXPECT_FALSE(core::bitIdentical(deep.image, renderReference(scene, settings).image));
}

TEST(RendererCounters, ReflectedRaysGrowWithDepth) {
  const core::Scene scene = core::makeBalls(2);
  RenderSettings settings = settingsFor(imageSide(), core::Sampling::Centers);
  std::uint64_t previous = 0;
  for (int depth = 2; depth <= 4; ++depth) {
    settings.shading.maxDepth = depth;
    const std::uint64_t reflected =
        renderImageParallel(scene, settings).counters.of(core::RayKind::Reflected);
    EXPECT_GT(reflected, previous) << "depth " << depth;
    previous = reflected;
  }
}

// Section 3.4's contribution form: with no lights, no diffuse term (so no ambient either) and a black
// background, no contribution can be anything but zero, and every pixel must be exactly black.
TEST(ContributionForm, NoLightNoDiffuseAndBlackBackgroundGiveABlackImage) {
  core::Scene scene = core::makeBalls(1);
  scene.lights.clear();
  for (core::Material& material : scene.materials) material.kd = 0;
  scene.background = core::Color(0);
  for (core::Sampling sampling : {core::Sampling::Centers, core::Sampling::Corners}) {
    const RenderSettings settings = settingsFor(16, sampling);
    for (const RenderResult& r : {renderReference(scene, settings), renderImageParallel(scene, settings)}) {
      for (const core::Color& p : r.image.pixels) ASSERT_EQ(p, core::Color(0)) << r.mode;
      EXPECT_EQ(r.counters.of(core::RayKind::Light), 0u) << r.mode;
      EXPECT_GT(r.counters.of(core::RayKind::Reflected), 0u) << r.mode;  // the tree is still traced
    }
  }
}

// Without lights the SPD's sqrt(L)/(2L) has no value; the ambient is its value at L = 1, so a white
// diffuse sphere seen head-on shows 0.5 (issue 45's repro, black before), the same in every renderer and
// precision.
TEST(ContributionForm, NoLightsLeaveTheAmbientAtOneHalf) {
  const core::Scene scene = core::readNff(testing_support::sourcePath("tests/data/nff/no_lights.nff"));
  ASSERT_TRUE(scene.lights.empty());
  RenderSettings settings = settingsFor(32, core::Sampling::Centers);
  for (const core::Precision precision : {core::Precision::Double, core::Precision::Float}) {
    settings.precision = precision;
    const RenderResult reference = renderReference(scene, settings);
    EXPECT_EQ(reference.image.at(16, 16), core::Color(0.5)) << core::nameOf(precision);
    EXPECT_EQ(reference.image.at(0, 0), core::Color(0)) << "the background";
    EXPECT_EQ(reference.counters.of(core::RayKind::Light), 0u);
    EXPECT_TRUE(core::bitIdentical(renderImageParallel(scene, settings).image, reference.image));
  }
}

// A scene with no objects is all background, to the frame buffer's 2^-40 resolution.
TEST(ContributionForm, EmptySceneIsAllBackground) {
  core::Scene scene = core::makeBalls(1);
  scene.objects.clear();
  scene.background = core::Color(0.25, 0.5, 0.7);
  for (core::Sampling sampling : {core::Sampling::Centers, core::Sampling::Corners}) {
    const RenderSettings settings = settingsFor(8, sampling);
    for (const RenderResult& r : {renderReference(scene, settings), renderImageParallel(scene, settings)}) {
      for (const core::Color& p : r.image.pixels)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(p[c], scene.background[c], 0x1p-39) << r.mode;
      EXPECT_EQ(r.counters.totalRays(), r.counters.of(core::RayKind::Eye)) << r.mode;
    }
  }
}

}  // namespace
}  // namespace raycube::host
