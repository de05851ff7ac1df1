// The host's pruning index (host/prepare/box_tree.h) finds exactly what testing every box finds, in ascending
// order, with or without taking whole the subtrees that lie inside the query (its shape a BVH's); the scene's
// cover holds every box.
#include "host/prepare/box_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/whitted.h"

namespace raycube::host {
namespace {

bool overlaps(const core::Box& a, const core::Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// The shape of a BVH over spheres at the boxes' centres: any tree over the same objects answers the same.
core::BvhShape shapeOver(const std::vector<core::Box>& boxes) {
  core::Scene scene;
  scene.materials.push_back(core::Material{});
  for (const core::Box& b : boxes) scene.objects.push_back(core::Object{core::Sphere{b.center(), 1.0}});
  const core::Whitted shading(scene, core::ShadingOptions{});
  return core::Bvh(scene, shading).shape();
}

TEST(BoxTree, QueryFindsWhatTestingEveryBoxFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-100, 100), size(0, 5);
  for (std::size_t count : {0u, 1u, 3u, 17u, 1000u}) {
    std::vector<core::Box> boxes;
    for (std::size_t i = 0; i < count; ++i) {
      const core::Vec3 lo(at(rng), at(rng), at(rng));
      boxes.push_back(core::Box{lo, lo + core::Vec3(size(rng), size(rng), size(rng))});
    }
    // Many identical boxes too.
    if (count == 1000) boxes.insert(boxes.end(), 50, boxes.front());
    const BoxTree tree(boxes, shapeOver(boxes));
    for (int q = 0; q < 20; ++q) {
      const core::Vec3 lo(at(rng), at(rng), at(rng));
      const core::Box region{lo, lo + core::Vec3(40, 40, 40)};
      std::vector<std::uint32_t> expected;
      for (std::uint32_t i = 0; i < boxes.size(); ++i)
        if (overlaps(boxes[i], region)) expected.push_back(i);
      EXPECT_EQ(tree.query([&](const core::Box& b) { return overlaps(b, region); }), expected) << count;
      // Subtrees found whole when their box lies inside the region: the same answer.
      auto inside = [&](const core::Box& b) {
        for (int k = 0; k < 3; ++k)
          if (b.lo[k] < region.lo[k] || b.hi[k] > region.hi[k]) return false;
        return true;
      };
      EXPECT_EQ(tree.query([&](const core::Box& b) { return overlaps(b, region); }, inside), expected)
          << count;
    }
    EXPECT_EQ(tree.query([](const core::Box&) { return true; }).size(), boxes.size());
  }
}

bool contains(const core::Box& outer, const core::Box& inner) {
  for (int k = 0; k < 3; ++k)
    if (inner.lo[k] < outer.lo[k] || inner.hi[k] > outer.hi[k]) return false;
  return true;
}

double volumeOf(const std::vector<core::Box>& boxes) {
  double v = 0;
  for (const core::Box& b : boxes) v += b.extent().x * b.extent().y * b.extent().z;
  return v;
}

// Where the scene lies (node/scene_bounds.h): at most the boxes asked for, every box inside one of them, and
// two boxes for two far-apart clusters, not one box spanning both.
TEST(BoxTree, CoverHoldsEveryBoxInAtMostTheBoxesAsked) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(0, 10), size(0, 1);
  std::vector<core::Box> boxes;
  for (int i = 0; i < 500; ++i) {
    const core::Vec3 lo = core::Vec3(at(rng), at(rng), at(rng)) + core::Vec3(i % 2 ? 1000 : 0, 0, 0);
    boxes.push_back(core::Box{lo, lo + core::Vec3(size(rng), size(rng), size(rng))});
  }
  EXPECT_TRUE(medianCover({}, 16).empty());
  std::vector<double> volumes;
  for (std::size_t most : {1u, 2u, 16u, 64u}) {
    const std::vector<core::Box> cover = medianCover(boxes, most);
    ASSERT_GE(cover.size(), 1u);
    EXPECT_LE(cover.size(), most);
    for (const core::Box& b : boxes)
      EXPECT_TRUE(std::any_of(cover.begin(), cover.end(), [&](const core::Box& c) { return contains(c, b); }))
          << most;
    volumes.push_back(volumeOf(cover));
  }
  EXPECT_LT(volumes[1], volumes[0] / 20);  // the two clusters apart, not the box of both
  // Many identical boxes: their centres do not spread, so the median splits stop and the cover is their box.
  const std::vector<core::Box> same(300, boxes.front());
  EXPECT_EQ(medianCover(same, 64).size(), 1u);
  EXPECT_TRUE(contains(medianCover(same, 64).front(), boxes.front()));
}

}  // namespace
}  // namespace raycube::host
