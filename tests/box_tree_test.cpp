// The host's pruning index (host/box_tree.h) finds exactly what testing every box finds, in ascending order,
// with or without taking whole the subtrees that lie inside the query.
#include "host/box_tree.h"

#include <gtest/gtest.h>

#include <random>

namespace raycube::host {
namespace {

bool overlaps(const core::Box& a, const core::Box& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
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
    // Many identical boxes too: the median split must still end.
    if (count == 1000) boxes.insert(boxes.end(), 50, boxes.front());
    const BoxTree tree(boxes);
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
      EXPECT_EQ(tree.query([&](const core::Box& b) { return overlaps(b, region); }, inside), expected) << count;
    }
    EXPECT_EQ(tree.query([](const core::Box&) { return true; }).size(), boxes.size());
  }
}

}  // namespace
}  // namespace raycube::host
