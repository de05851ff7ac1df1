#include "core/spd/balls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/nff_reader.h"
#include "test_support.h"

namespace raycube::core {
namespace {

// SPD prints %g (6 significant digits); every coordinate of the flake is below 1.2 in magnitude.
constexpr double kTolerance = 1e-5;

void expectNear(const Vec3& actual, const Vec3& expected, const std::string& what) {
  EXPECT_NEAR(actual.x, expected.x, kTolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, kTolerance) << what;
  EXPECT_NEAR(actual.z, expected.z, kTolerance) << what;
}

class BallsMatchesSpd : public testing::TestWithParam<int> {};

TEST_P(BallsMatchesSpd, ElementByElement) {
  const int size = GetParam();
  const Scene generated = makeBalls(size);
  const Scene file = readNff(testing_support::scenePath("balls" + std::to_string(size) + ".nff"));
  EXPECT_EQ(generated.name, file.name);

  expectNear(generated.background, file.background, "background");
  expectNear(generated.camera.from, file.camera.from, "from");
  expectNear(generated.camera.at, file.camera.at, "at");
  expectNear(generated.camera.up, file.camera.up, "up");
  EXPECT_EQ(generated.camera.angleDegrees, file.camera.angleDegrees);
  EXPECT_EQ(generated.camera.hither, file.camera.hither);
  EXPECT_EQ(generated.camera.width, file.camera.width);
  EXPECT_EQ(generated.camera.height, file.camera.height);

  ASSERT_EQ(generated.lights.size(), file.lights.size());
  for (std::size_t i = 0; i < file.lights.size(); ++i) {
    expectNear(generated.lights[i].position, file.lights[i].position, "light " + std::to_string(i));
    EXPECT_EQ(generated.lights[i].hasColor, file.lights[i].hasColor);
  }

  ASSERT_EQ(generated.materials.size(), file.materials.size());
  for (std::size_t i = 0; i < file.materials.size(); ++i) {
    const Material& g = generated.materials[i];
    const Material& f = file.materials[i];
    expectNear(g.color, f.color, "material color " + std::to_string(i));
    EXPECT_EQ(g.kd, f.kd);
    EXPECT_EQ(g.ks, f.ks);
    EXPECT_EQ(g.shine, f.shine);
    EXPECT_EQ(g.transmission, f.transmission);
    EXPECT_EQ(g.ior, f.ior);
  }

  ASSERT_EQ(generated.objects.size(), file.objects.size());
  for (std::size_t i = 0; i < file.objects.size(); ++i) {
    const Object& g = generated.objects[i];
    const Object& f = file.objects[i];
    const std::string where = "object " + std::to_string(i);
    ASSERT_EQ(g.shape.index(), f.shape.index()) << where;
    EXPECT_EQ(g.material, f.material) << where;
    EXPECT_EQ(g.insideVisible, f.insideVisible) << where;
    if (const auto* sphere = std::get_if<Sphere>(&f.shape)) {
      const auto& mine = std::get<Sphere>(g.shape);
      expectNear(mine.center, sphere->center, where);
      EXPECT_NEAR(mine.radius, sphere->radius, kTolerance) << where;
    } else {
      const auto& polygon = std::get<Polygon>(f.shape);
      const auto& mine = std::get<Polygon>(g.shape);
      ASSERT_EQ(mine.vertices.size(), polygon.vertices.size()) << where;
      for (std::size_t v = 0; v < polygon.vertices.size(); ++v)
        expectNear(mine.vertices[v], polygon.vertices[v], where);
    }
    if (HasFailure()) FAIL() << "first mismatch at " << where;
  }
}

INSTANTIATE_TEST_SUITE_P(Sizes, BallsMatchesSpd, testing::Values(1, 2, 3, 4));

TEST(Balls, Size2HasNinetyOneSpheresOneFloorAndThreeLights) {
  const Scene scene = makeBalls(2);
  EXPECT_EQ(scene.name, "balls2");
  EXPECT_EQ(scene.objects.size(), 92u);
  EXPECT_EQ(scene.lights.size(), 3u);
  EXPECT_TRUE(std::holds_alternative<Polygon>(scene.objects.front().shape));
  const SceneFeatures features = scene.features();
  EXPECT_TRUE(features.spheres);
  EXPECT_TRUE(features.polygons);
  EXPECT_TRUE(features.reflection);
  EXPECT_FALSE(features.transmission);
}

TEST(Balls, SphereCountGrowsByPowersOfNine) {
  EXPECT_EQ(makeBalls(1).objects.size(), 1u + 10u);
  EXPECT_EQ(makeBalls(3).objects.size(), 1u + 820u);
  EXPECT_EQ(makeBalls(5).objects.size(), 1u + 66430u);
}

// From size 5 on, some children's axes are a rounding step off +Z and have no rotation axis: balls.c keeps
// the zero vector (lib_normalize_vector), where normalizing it gave NaN spheres and crashed the BVH build.
TEST(Balls, Size5HasOnlyFiniteSpheres) {
  const Scene scene = makeBalls(5);
  ASSERT_EQ(scene.objects.size(), 66431u);
  for (const Object& object : scene.objects)
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
      ASSERT_TRUE(std::isfinite(sphere->center.x) && std::isfinite(sphere->center.y) &&
                  std::isfinite(sphere->center.z))
          << "a sphere of radius " << sphere->radius;
    }
}

TEST(Balls, RejectsSizesOutsideOneToSix) {
  for (int size : {0, -1, 7, 100}) {
    try {
      makeBalls(size);
      FAIL() << "accepted size " << size;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("got " + std::to_string(size)), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace raycube::core
