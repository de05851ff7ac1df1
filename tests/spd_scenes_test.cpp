// The built-in SPD generators (core/spd/generators.h) against what the SPD documents: primitive counts per
// size (SPD-README's "total prim." at the default sizes, the C files' header tables otherwise), and the
// committed default-size scenes/*.nff, which are the generators' output (and byte for byte the SPD programs'
// own).
#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <variant>

#include "core/nff_reader.h"
#include "core/nff_writer.h"
#include "core/spd/balls.h"
#include "core/spd/generators.h"
#include "scene_equality.h"
#include "test_support.h"

namespace raycube::core {
namespace {

struct Counts {
  std::size_t spheres = 0, cylinders = 0, polygons = 0;
  std::size_t total() const { return spheres + cylinders + polygons; }
};

Counts countsOf(const Scene& scene) {
  Counts counts;
  for (const Object& object : scene.objects) {
    if (std::holds_alternative<Sphere>(object.shape)) ++counts.spheres;
    if (std::holds_alternative<Cone>(object.shape)) ++counts.cylinders;
    if (std::holds_alternative<Polygon>(object.shape)) ++counts.polygons;
  }
  return counts;
}

struct Expected {
  const char* name;
  int size;
  std::size_t spheres, cylinders, polygons;
};

// SPD-README: total prim. mount 8196, rings 8401, tetra 4096 at the default sizes. Header comments: rings.c
// 30/150/420/4200 spheres and cylinders at 1/2/3/7 plus 1 square; mount.c 8/32/128/8192 triangles plus 4
// spheres at 1/2/3/6; tetra.c 4^size triangles; lattice.c 8/27/64/216/2197 spheres and 12/54/144/540/6084
// cylinders at 1/2/3/5/12; sombrero.c a 32/64/128 square grid at 1/2/3, two triangles per square. jacks.c's
// table is blank ("xx"): one jack is 3 cylinders and 6 spheres, with 8 half-size jacks in it per level.
const Expected kExpected[] = {
    {"rings", 1, 30, 30, 1},
    {"rings", 2, 150, 150, 1},
    {"rings", 3, 420, 420, 1},
    {"rings", 7, 4200, 4200, 1},
    {"mount", 1, 4, 0, 8},
    {"mount", 2, 4, 0, 32},
    {"mount", 3, 4, 0, 128},
    {"mount", 6, 4, 0, 8192},
    {"tetra", 1, 0, 0, 4},
    {"tetra", 2, 0, 0, 16},
    {"tetra", 3, 0, 0, 64},
    {"tetra", 6, 0, 0, 4096},
    {"lattice", 1, 8, 12, 0},
    {"lattice", 2, 27, 54, 0},
    {"lattice", 3, 64, 144, 0},
    {"lattice", 5, 216, 540, 0},
    {"lattice", 12, 2197, 6084, 0},
    {"jacks", 1, 6, 3, 0},
    {"jacks", 2, 54, 27, 0},
    {"jacks", 4, 3510, 1755, 0},
    {"sombrero", 1, 0, 0, 2 * 31 * 31},
    {"sombrero", 2, 0, 0, 2 * 63 * 63},
    {"sombrero", 3, 0, 0, 2 * 127 * 127},
};

class SpdGeneratorCounts : public testing::TestWithParam<Expected> {};

TEST_P(SpdGeneratorCounts, MatchTheSpdsDocumentedNumbers) {
  const Expected& e = GetParam();
  const Scene scene = makeSpdScene(e.name, e.size);
  const Counts counts = countsOf(scene);
  EXPECT_EQ(scene.name, std::string(e.name) + std::to_string(e.size));
  EXPECT_EQ(counts.spheres, e.spheres);
  EXPECT_EQ(counts.cylinders, e.cylinders);
  EXPECT_EQ(counts.polygons, e.polygons);
  EXPECT_EQ(counts.total(), scene.objects.size()) << "no patches in OUTPUT_CURVES mode";
}

INSTANTIATE_TEST_SUITE_P(All, SpdGeneratorCounts, testing::ValuesIn(kExpected),
                         [](const testing::TestParamInfo<Expected>& info) {
                           return std::string(info.param.name) + std::to_string(info.param.size);
                         });

TEST(SpdGenerators, DefaultSizesAreTheSpdsTotals) {
  EXPECT_EQ(makeSpdScene("mount").objects.size(), 8196u);    // SPD-README total prim.
  EXPECT_EQ(makeSpdScene("rings").objects.size(), 8401u);    // SPD-README total prim.
  EXPECT_EQ(makeSpdScene("tetra").objects.size(), 4096u);    // SPD-README total prim.
  EXPECT_EQ(makeSpdScene("lattice").objects.size(), 8281u);  // lattice.c: 2197 + 6084
  EXPECT_EQ(makeSpdScene("balls").objects.size(), 7382u);    // SPD-README total prim.
}

// The default-size files in scenes/ are what `raycube spd NAME` writes, byte for byte (and, checked when
// they were made, what the SPD programs print), and read back as the generator's scene, number for number.
class SpdDefaultSceneFile : public testing::TestWithParam<const char*> {};

TEST_P(SpdDefaultSceneFile, IsTheGeneratorsScene) {
  const SpdGenerator& generator = spdGenerator(GetParam());
  const Scene generated = generator.make(generator.defaultSize);
  const std::string file = generated.name + ".nff";
  EXPECT_EQ(nffText(generated), testing_support::slurp(testing_support::scenePath(file)));
  const Scene read = readNff(testing_support::scenePath(file));
  EXPECT_EQ(read.name, generated.name);
  EXPECT_TRUE(testing_support::sameScene(generated, read));
}

INSTANTIATE_TEST_SUITE_P(All, SpdDefaultSceneFile,
                         testing::Values("rings", "mount", "tetra", "lattice", "jacks", "sombrero"));

TEST(SpdGenerators, BallsIsMakeBalls) {
  EXPECT_TRUE(testing_support::sameScene(makeSpdScene("balls", 2), makeBalls(2)));
  EXPECT_EQ(makeSpdScene("balls").name, "balls4");
}

TEST(SpdGenerators, UnknownNameListsTheKnownOnes) {
  try {
    makeSpdScene("teapot", 2);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("teapot"), std::string::npos) << what;
    for (const SpdGenerator& generator : spdGenerators())
      EXPECT_NE(what.find(generator.name), std::string::npos) << what;
  }
}

TEST(SpdGenerators, SizesOutsideTheRangeAreRefused) {
  for (const SpdGenerator& generator : spdGenerators()) {
    for (const int size : {-1, 0, generator.maxSize + 1}) {
      try {
        generator.make(size);
        ADD_FAILURE() << generator.name << " accepted size " << size;
      } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(std::to_string(generator.maxSize)), std::string::npos) << what;
        EXPECT_NE(what.find("got " + std::to_string(size)), std::string::npos) << what;
      }
    }
    EXPECT_GE(generator.maxSize, generator.defaultSize) << generator.name;
  }
}

}  // namespace
}  // namespace raycube::core
