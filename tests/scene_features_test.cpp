// A scene knows what it uses, so a renderer never pays for a feature it does not need (no refraction or
// transmission products without T > 0, no cone or patch code without cones or patches).
#include <gtest/gtest.h>

#include <filesystem>

#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "core/whitted.h"
#include "test_support.h"

namespace raycube::core {
namespace {

Scene shipped(const char* name) {
  return readNff(testing_support::scenePath(name));
}

TEST(SceneFeatures, BallsUsesSpheresAPolygonAndReflectionOnly) {
  const SceneFeatures f = makeBalls(2).features();
  EXPECT_TRUE(f.spheres);
  EXPECT_TRUE(f.polygons);
  EXPECT_TRUE(f.reflection);
  EXPECT_FALSE(f.transmission);
  EXPECT_FALSE(f.cones);
  EXPECT_FALSE(f.patches);
  EXPECT_EQ(f.lightCount, 3u);
}

TEST(SceneFeatures, EachShippedSceneReportsWhatItUses) {
  EXPECT_TRUE(shipped("gears1.nff").features().transmission);
  EXPECT_TRUE(shipped("tree1.nff").features().cones);
  EXPECT_TRUE(shipped("teapot2.nff").features().patches);
  EXPECT_FALSE(shipped("teapot2.nff").features().transmission);
  const SceneFeatures jacks = shipped("jacks1.nff").features();
  EXPECT_TRUE(jacks.cones && jacks.spheres);
  EXPECT_FALSE(jacks.polygons || jacks.patches || jacks.transmission);
  EXPECT_EQ(shipped("tree1.nff").features().lightCount, 7u);
}

// Light rays multiply transmissions only in scenes that have some; elsewhere any blocker answers.
TEST(SceneFeatures, ShadingKnowsWhetherLightRaysMustMultiplyTransmissions) {
  const Scene balls = makeBalls(1), gears = shipped("gears1.nff");
  EXPECT_FALSE(Whitted(balls, {}).sceneTransmits());
  EXPECT_TRUE(Whitted(gears, {}).sceneTransmits());
}

// Reflected or refracted rays exist only with Ks or T somewhere and a depth above one: otherwise only eye
// rays meet objects (so no light ray starts behind the eye, and the machine prunes accordingly).
TEST(SceneFeatures, ShadingKnowsWhetherRaysOtherThanEyeRaysMeetObjects) {
  const Scene balls = makeBalls(1), gears = shipped("gears1.nff"), tree = shipped("tree1.nff");
  EXPECT_TRUE(Whitted(balls, {}).spawnsSecondaryRays());  // reflective spheres
  EXPECT_TRUE(Whitted(gears, {}).spawnsSecondaryRays());  // transmitting gears
  EXPECT_FALSE(Whitted(tree, {}).spawnsSecondaryRays());  // matte tree and ground
  ShadingOptions eyeRaysOnly;
  eyeRaysOnly.maxDepth = 1;
  EXPECT_FALSE(Whitted(balls, eyeRaysOnly).spawnsSecondaryRays());
}

}  // namespace
}  // namespace raycube::core
