// core/nff_writer.h: what it writes reads back as the same scene, number for number.
#include "core/nff_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/nff_reader.h"
#include "core/spd/balls.h"
#include "scene_equality.h"
#include "test_support.h"

namespace raycube::core {
namespace {

// The reader normalises patch normals: a unit normal normalised again may move by an ulp or two.
constexpr double kRenormalised = 1e-15;

Scene roundTrip(const Scene& scene) {
  return parseNff(nffText(scene, "written by nff_writer_test"), scene.name + ".nff");
}

TEST(NffWriter, EveryShippedSceneReadsBackTheSame) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing_support::sourcePath("scenes"))) {
    if (entry.path().extension() != ".nff") continue;
    const Scene scene = readNff(entry.path());
    EXPECT_TRUE(testing_support::sameScene(scene, roundTrip(scene), kRenormalised)) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 10);
}

// makeBalls' numbers are full doubles, not SPD text: the shortest round-trip digits keep every bit.
TEST(NffWriter, FullPrecisionNumbersSurvive) {
  const Scene balls = makeBalls(2);
  EXPECT_TRUE(testing_support::sameScene(balls, roundTrip(balls)));
}

TEST(NffWriter, InsideVisibleColouredLightsPatchesAndMaterialsOutOfOrder) {
  const Scene scene = parseNff(R"(b 0.1 0.2 0.3
v
from 0 -5 0.30000000000000004
at 0 0 0
up 0 0 1
angle 40
hither 0.5
resolution 64 48
l 1 2 3 0.5 0.25 1
l -1 -2 3
f 1 0 0 0.5 0.5 3 0 1
f 0 1 0 0.7 0 1 0.5 1.5
s 0 0 0 -1
c 0 0 0 -0.5 0 0 1 -0.25
f 0 0 1 1 0 1 0 0
pp 3
0 0 0 0 0 1
1 0 0 0 0.6 0.8
0 1 0 0 0 1
)",
                               "features.nff");
  Scene mixed = scene;
  mixed.objects[1].material = 0;  // back to an earlier material: printed again, with a new index
  EXPECT_TRUE(testing_support::sameScene(scene, roundTrip(scene), kRenormalised));
  const Scene again = roundTrip(mixed);
  ASSERT_EQ(again.objects.size(), 3u);
  EXPECT_TRUE(testing_support::sameMaterial(again.materials[again.objects[1].material], mixed.materials[0]));
  EXPECT_TRUE(testing_support::sameShape(again.objects[1].shape, mixed.objects[1].shape));
  EXPECT_TRUE(again.objects[1].insideVisible);
  EXPECT_TRUE(testing_support::sameMaterial(again.materials[again.objects[2].material], mixed.materials[2]));
}

}  // namespace
}  // namespace raycube::core
