// What a processor holds (node/region_database.h): the union of its lists, once each and in the scene's
// order; its lists rewritten into local indices naming the same objects; one BVH per database, shared by
// every processor holding that very database, and in place the host's tree over what it holds
// (node/database_bvh.h).
#include "node/region_database.h"

#include <gtest/gtest.h>

#include <memory>
#include <tuple>
#include <variant>

#include "core/nff_reader.h"
#include "core/view.h"
#include "node/database_bvh.h"

namespace raycube::node {
namespace {

const char* kSixSpheres =
    "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 16 16\n"
    "l 5 5 5\nf 0.8 0.8 0.8 0.5 0.5 10 0 1\n"
    "s -5 0 0 0.5\ns -3 0 0 0.5\ns -1 0 0 0.5\ns 1 0 0 0.5\ns 3 0 0 0.5\ns 5 0 0 0.5\n";

class RegionDatabaseTest : public ::testing::Test {
 protected:
  RegionDatabaseTest() : scene_(core::parseNff(kSixSpheres, "six.nff")), view_(scene_.camera, 16, 16, core::Sampling::Centers) {
    for (const core::Object& o : scene_.objects)
      boxes_.push_back(eyeBoxOf(o, view_, 2 * scene_.largestCoordinate()));
  }
  core::Scene scene_;
  core::View view_;
  std::vector<EyeBox> boxes_;
};

TEST_F(RegionDatabaseTest, HoldsTheUnionOfItsListsOnceEachInTheScenesOrder) {
  std::vector<std::uint32_t> region{4, 1}, light{1, 5, 4}, empty;
  std::vector<std::uint32_t>* lists[] = {&region, &light, &empty};
  EXPECT_EQ(heldObjectsOf(lists, scene_.objects.size()), (std::vector<std::uint32_t>{1, 4, 5}));
  // Short ascending lists (as the host's queries give them) in a large scene are merged, long ones flagged:
  // the same union either way, an object named twice in a list or in several held once.
  std::vector<std::uint32_t> ascending{1, 4, 4}, lights{0, 1, 5}, more{5, 6};
  std::vector<std::uint32_t>* sorted[] = {&ascending, &lights, &empty, &more};
  for (std::size_t sceneObjects : {7u, 1000u})
    EXPECT_EQ(heldObjectsOf(sorted, sceneObjects), (std::vector<std::uint32_t>{0, 1, 4, 5, 6}))
        << sceneObjects;
}

TEST_F(RegionDatabaseTest, ListsNameTheSameObjectsInLocalIndices) {
  for (const std::vector<std::uint32_t>& named :
       {std::vector<std::uint32_t>{5, 2, 3}, std::vector<std::uint32_t>{2, 0, 1}, std::vector<std::uint32_t>{}}) {
    std::vector<std::uint32_t> region = named;
    std::vector<std::uint32_t> rear = named.empty() ? std::vector<std::uint32_t>{} : std::vector{named[0]};
    std::vector<std::uint32_t>* lists[] = {&region, &rear};
    const RegionDatabase db = gatherRegionDatabase(scene_, lists);
    ASSERT_EQ(db.scene.objects.size(), named.size());
    for (std::size_t i = 0; i < named.size(); ++i) {
      const std::uint32_t global = db.globalIds[region[i]];
      EXPECT_EQ(global, named[i]);
      EXPECT_EQ(std::get<core::Sphere>(db.scene.objects[region[i]].shape).center,
                std::get<core::Sphere>(scene_.objects[global].shape).center);
    }
    if (!named.empty()) {
      EXPECT_EQ(db.globalIds[rear[0]], named[0]);
    }
  }
}

TEST_F(RegionDatabaseTest, TheRegionsObjectsComeWithTheirEyeBoxesInTheirOrder) {
  const std::vector<std::uint32_t> region{5, 2, 3};
  const std::vector<EyeBox> boxes = eyeBoxesOf(boxes_, region);
  ASSERT_EQ(boxes.size(), region.size());
  for (std::size_t k = 0; k < region.size(); ++k) {
    EXPECT_EQ(boxes[k].lo, boxes_[region[k]].lo);
    EXPECT_EQ(boxes[k].hi, boxes_[region[k]].hi);
  }
  EXPECT_TRUE(eyeBoxesOf(boxes_, {}).empty());
}

TEST_F(RegionDatabaseTest, ProcessorsHoldingTheSameDatabaseShareOneTree) {
  std::vector<std::uint32_t> held{0, 2, 3};
  auto database = std::make_shared<const RegionDatabase>(regionDatabaseOf(scene_, held));
  auto equal = std::make_shared<const RegionDatabase>(regionDatabaseOf(scene_, held));
  const auto tree = sharedBvhOf<double>(database, core::ShadingOptions{});
  EXPECT_EQ(sharedBvhOf<double>(database, core::ShadingOptions{}), tree);
  EXPECT_EQ(tree->database, database);
  EXPECT_NE(sharedBvhOf<double>(equal, core::ShadingOptions{}), tree);  // another copy: its own tree
  EXPECT_EQ(&tree->bvh, &sharedBvhOf<double>(database, core::ShadingOptions{})->bvh);
}

// Read in place, a database holds no object: its indices are the scene's own, its lists stay as they are,
// and its tree finds the held objects, and only them, where a copy's finds their copies.
TEST_F(RegionDatabaseTest, ReadInPlaceItNamesTheScenesObjectsByTheirOwnIndices) {
  const std::vector<std::uint32_t> held{1, 4, 5};
  auto inPlace = std::make_shared<const RegionDatabase>(regionDatabaseIn(scene_, scene_.features(), held));
  auto copy = std::make_shared<const RegionDatabase>(regionDatabaseOf(scene_, held));
  EXPECT_EQ(&inPlace->traced(), &scene_);
  EXPECT_TRUE(inPlace->scene.objects.empty());
  EXPECT_EQ(inPlace->size(), held.size());
  EXPECT_EQ(inPlace->heldIndices(), held);
  EXPECT_TRUE(inPlace->wholeIdOf().empty());
  EXPECT_EQ(copy->heldIndices(), (std::vector<std::uint32_t>{0, 1, 2}));
  std::vector<std::uint32_t> region{4, 1}, rear{5};
  std::vector<std::uint32_t>* lists[] = {&region, &rear};
  toLocalIndices(*inPlace, lists);
  EXPECT_EQ(region, (std::vector<std::uint32_t>{4, 1}));
  EXPECT_EQ(rear, (std::vector<std::uint32_t>{5}));

  const core::Whitted shading(scene_, core::ShadingOptions{});
  const core::BvhShape shape = core::Bvh(scene_, shading).shape();
  const DatabaseBvh<double> inPlaceTree(inPlace, core::ShadingOptions{}, &shape);
  const DatabaseBvh<double> copyTree(copy, core::ShadingOptions{}, &shape);
  core::TraceCounters counters;
  // Along the row of spheres from each end and from between them: the nearest held sphere, never 0, 2 or 3.
  for (const auto& [x, dx, expected] : {std::tuple{-10.0, 1.0, 1u}, std::tuple{-2.0, 1.0, 4u},
                                        std::tuple{10.0, -1.0, 5u}, std::tuple{2.0, -1.0, 1u}}) {
    const core::Ray ray{{x, 0, 0}, {dx, 0, 0}, 0, core::kInfinity};
    const core::Hit a = inPlaceTree.bvh.closestHit(ray, counters), b = copyTree.bvh.closestHit(ray, counters);
    EXPECT_EQ(a.object, expected) << "from x = " << x;
    ASSERT_TRUE(b.found());
    EXPECT_EQ(copy->globalIds[b.object], expected);
    EXPECT_EQ(a.t, b.t);
  }
}

// A processor reading the scene in place answers its light rays with the host's tree over the whole scene,
// passing over the objects it does not hold: the answers of a tree over its database (a copy's), and a
// float machine, whose rays the host's double tree cannot take, keeps a tree of its own.
TEST_F(RegionDatabaseTest, LightRaysInPlaceMeetOnlyTheHeldObjectsOfTheHostsTree) {
  const std::vector<std::uint32_t> held{1, 4};  // the spheres at x = -3 and x = 3
  auto inPlace = std::make_shared<const RegionDatabase>(regionDatabaseIn(scene_, scene_.features(), held));
  auto copy = std::make_shared<const RegionDatabase>(regionDatabaseOf(scene_, held));
  const auto hostTree = std::make_shared<const SceneTree>(scene_, core::ShadingOptions{});
  const LightRayTree<double> overHostTree(inPlace, core::ShadingOptions{}, nullptr, hostTree);
  const LightRayTree<double> overCopy(copy, core::ShadingOptions{}, nullptr, hostTree);  // not in place
  const LightRayTree<float> inFloat(inPlace, core::ShadingOptions{}, nullptr, hostTree);
  core::TraceCounters counters;
  std::vector<core::Hit> crossed;
  // Segments along the row: between the unheld spheres at -1 and 1 (light passes), through the unheld one
  // at -5 and the held one at -3 (blocked by -3), from x = -2 to x = 2.5 (no sphere held on the way).
  for (const auto& [x0, x1, expected, blocker] :
       {std::tuple{-2.0, 2.0, 1.0, 0u}, std::tuple{-10.0, -2.0, 0.0, 1u}, std::tuple{-2.0, 2.4, 1.0, 0u},
        std::tuple{2.0, 10.0, 0.0, 4u}}) {
    const core::Ray ray{{x0, 0, 0}, {1, 0, 0}, 0, x1 - x0};
    EXPECT_EQ(overHostTree.transmission(ray, counters, crossed), expected) << x0 << " to " << x1;
    if (expected == 0) {
      ASSERT_EQ(crossed.size(), 1u);
      EXPECT_EQ(crossed[0].object, blocker);  // a global index: the scene is read in place
    }
    EXPECT_EQ(overCopy.transmission(ray, counters, crossed), expected) << x0 << " to " << x1;
    const core::BasicRay<float> floatRay{{float(x0), 0, 0}, {1, 0, 0}, 0, float(x1 - x0)};
    EXPECT_EQ(inFloat.transmission(floatRay, counters, crossed), expected) << x0 << " to " << x1;
  }
  // The whole tree, unfiltered, is blocked by the unheld spheres too.
  EXPECT_EQ(hostTree->bvh.transmission(core::Ray{{-2, 0, 0}, {1, 0, 0}, 0, 4}, counters, crossed), 0.0);
}

}  // namespace
}  // namespace raycube::node
