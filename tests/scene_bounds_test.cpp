// Where the scene lies (node/scene_bounds.h): the last t at which a ray is inside one of the boxes, from a
// given t on, or none when it meets none of them there. And what lies ahead of a ray leaving its region
// (node/regions_ahead.h): whether the regions it would cross hold anything its parts there could meet.
#include "node/scene_bounds.h"

#include <gtest/gtest.h>

#include "node/regions_ahead.h"

namespace raycube::node {
namespace {

const std::vector<core::Box> kTwoBoxes{core::Box{{1, -1, -1}, {2, 1, 1}}, core::Box{{5, -1, -1}, {6, 1, 1}}};

TEST(SceneBounds, LastInsideIsTheFarthestExitAhead) {
  const core::Vec3 origin(0, 0, 0), alongX(1, 0, 0);
  EXPECT_NEAR(*lastInsideBounds(kTwoBoxes, origin, alongX, 0, core::kInfinity), 6, 1e-12);
  EXPECT_NEAR(*lastInsideBounds(kTwoBoxes, origin, alongX, 0, 3), 2, 1e-12);  // the far box beyond tMax
  EXPECT_NEAR(*lastInsideBounds(kTwoBoxes, origin, alongX, 5.5, core::kInfinity), 6, 1e-12);
}

TEST(SceneBounds, NoneWhenTheRayMeetsNoBoxAhead) {
  const core::Vec3 origin(0, 0, 0);
  EXPECT_FALSE(meetsBounds(kTwoBoxes, origin, core::Vec3(1, 0, 0), 6.5, core::kInfinity));
  EXPECT_FALSE(meetsBounds(kTwoBoxes, origin, core::Vec3(1, 0, 0), 3, 4));
  EXPECT_TRUE(meetsBounds(kTwoBoxes, origin, core::Vec3(1, 0, 0), 3, 5.5));
  EXPECT_FALSE(lastInsideBounds(kTwoBoxes, origin, core::Vec3(1, 0, 0), 6.5, core::kInfinity));  // past both
  EXPECT_FALSE(lastInsideBounds(kTwoBoxes, origin, core::Vec3(-1, 0, 0), 0, core::kInfinity));   // away
  EXPECT_FALSE(lastInsideBounds(kTwoBoxes, origin, core::Vec3(0, 1, 0), 0, core::kInfinity));    // beside
  EXPECT_FALSE(lastInsideBounds({}, origin, core::Vec3(1, 0, 0), 0, core::kInfinity));           // no scene
  // Between the boxes, up to tMax short of the next one.
  EXPECT_FALSE(lastInsideBounds(kTwoBoxes, origin, core::Vec3(1, 0, 0), 3, 4));
}

// A ray at a point inside a box meets it (settled without the slab test), unless its interval has ended;
// one leaving a box, on its face, still meets it; whichever box holds the point.
TEST(SceneBounds, ARayInsideABoxMeetsItWhileItsIntervalLasts) {
  const core::Vec3 origin(0, 0, 0), alongX(1, 0, 0);
  EXPECT_TRUE(meetsBounds(kTwoBoxes, origin, alongX, 1.5, core::kInfinity));
  EXPECT_TRUE(meetsBounds(kTwoBoxes, origin, alongX, 5.5, 5.5));
  EXPECT_TRUE(meetsBounds(kTwoBoxes, origin, alongX, 2, 2.5));   // on the first box's far face
  EXPECT_FALSE(meetsBounds(kTwoBoxes, origin, alongX, 5.5, 5));  // past its end
  EXPECT_TRUE(meetsBounds(kTwoBoxes, core::Vec3(5.5, 0, 0), core::Vec3(0, 0, -1), 0.5, core::kInfinity));
  EXPECT_FALSE(meetsBounds(kTwoBoxes, core::Vec3(5.5, 0, 0), core::Vec3(0, 0, -1), 1.5, core::kInfinity));
}

// A box holds the points of its faces and edges, none outside, and an empty box none.
TEST(SceneBounds, ABoxHoldsThePointsOfItsFaces) {
  const core::Box& box = kTwoBoxes.front();
  EXPECT_TRUE(box.holds(core::Vec3(1.5, 0, 0)));
  EXPECT_TRUE(box.holds(core::Vec3(1, 0, 0)));
  EXPECT_TRUE(box.holds(core::Vec3(2, 1, -1)));
  EXPECT_FALSE(box.holds(core::Vec3(2.000001, 0, 0)));
  EXPECT_FALSE(box.holds(core::Vec3(1.5, 0, -1.000001)));
  EXPECT_FALSE(core::Box{}.holds(core::Vec3(0, 0, 0)));
}

// A ray along a box's face, or parallel to a slab it lies in, is inside (the slab test's NaNs leave that
// slab unconstrained): conservative, never a ray ended that could touch a box.
TEST(SceneBounds, RaysGrazingABoxCountAsInside) {
  EXPECT_TRUE(lastInsideBounds(kTwoBoxes, core::Vec3(0, 1, 0), core::Vec3(1, 0, 0), 0, core::kInfinity));
  EXPECT_TRUE(lastInsideBounds(kTwoBoxes, core::Vec3(1, 0, 0), core::Vec3(0, 0, 1), 0, core::kInfinity));
}

// Three regions side by side, seen from the origin down -z (the eye frame's depth is -z, its s = x / depth):
// region 0 left of s(10), region 1 to s(20), region 2 beyond. A ray at depth 5 moving along +x crosses region
// 1 for x in about [-0.69, 0.69] (t in [1.31, 2.69] from x = -2) and stays in region 2 from there.
class RegionsAhead : public ::testing::Test {
 protected:
  RegionsAhead()
      : view_(core::Camera{}, 30, 10, core::Sampling::Centers),
        regions_(RegionMap::grid({0, 10, 20, 30}, {0, 10}, ScreenLines(view_))) {}

  bool nothingAheadOf(const core::Vec3& origin, const core::Vec3& direction, int next, double t,
                      double tMax = core::kInfinity) const {
    const EyeFrameRay er = EyeFrameRay::of(core::BasicRay<double>{origin, direction}, view_);
    return nothingAhead(regions_, regionBounds_, sceneBounds_, er, origin, direction, next, t, tMax);
  }

  const core::View view_;
  const RegionMap regions_;
  // Below the ray in region 1, and in region 2; the scene's bounds hold the ray's way through both.
  std::vector<core::Box> regionBounds_{core::Box{{-9, -4, -6}, {-8, -2, -4}},
                                       core::Box{{-1, -4, -6}, {1, -2, -4}},
                                       core::Box{{3, -4, -6}, {5, -2, -4}}};
  std::vector<core::Box> sceneBounds_{core::Box{{-10, -4, -10}, {10, 1, 0}}};
  const core::Vec3 from_{-2, 0, -5}, alongX_{1, 0, 0};
};

TEST_F(RegionsAhead, ARayMissingEveryRegionsObjectsOnItsWayOutMeetsNothing) {
  EXPECT_TRUE(nothingAheadOf(from_, alongX_, 1, 1.5));
  EXPECT_TRUE(nothingAheadOf(from_, alongX_, 2, 3));
  // Nothing known of the regions: the ray goes on.
  regionBounds_.clear();
  EXPECT_FALSE(nothingAheadOf(from_, alongX_, 1, 1.5));
}

// Only the ray's part in a region counts against that region's box: the box of region 1's objects reaching
// into region 2's part of the ray is not met; region 2's own box is.
TEST_F(RegionsAhead, OnlyTheRaysPartInARegionIsTestedAgainstItsObjects) {
  regionBounds_[1] = core::Box{{3, -1, -6}, {5, 1, -4}};
  EXPECT_TRUE(nothingAheadOf(from_, alongX_, 1, 1.5));
  regionBounds_[2] = regionBounds_[1];
  EXPECT_FALSE(nothingAheadOf(from_, alongX_, 1, 1.5));
  regionBounds_[2] = core::Box{};  // a region holding no object
  regionBounds_[1] = core::Box{{0, -1, -6}, {0.5, 1, -4}};
  EXPECT_FALSE(nothingAheadOf(from_, alongX_, 1, 1.5));
  EXPECT_TRUE(nothingAheadOf(from_, alongX_, 2, 3));
}

// A light ray reaching its light, or a ray leaving the scene's bounds, in a region whose objects it misses
// ends; one whose part in front of the eye ends there goes on (the rear objects lie behind the eye plane).
TEST_F(RegionsAhead, TheRayEndsWhereItsIntervalOrTheSceneEnds) {
  regionBounds_[2] = core::Box{{3, -1, -6}, {5, 1, -4}};
  EXPECT_FALSE(nothingAheadOf(from_, alongX_, 1, 1.5));
  EXPECT_TRUE(nothingAheadOf(from_, alongX_, 1, 1.5, 2.0));  // a light ray whose light is in region 1
  sceneBounds_ = {core::Box{{-10, -4, -10}, {0.5, 1, 0}}, regionBounds_[2]};
  EXPECT_FALSE(nothingAheadOf(from_, alongX_, 1, 1.5));
  sceneBounds_.pop_back();  // beyond region 1 the ray leaves the scene
  EXPECT_TRUE(nothingAheadOf(from_, alongX_, 1, 1.5));
  // Towards the eye plane (crossed at t = 2, in region 2): its rear part follows.
  const core::Vec3 nearEye(-1, 0, -2), towardsEye(1, 0, 1);
  EXPECT_FALSE(nothingAheadOf(nearEye, towardsEye, 1, 0.9));
}

}  // namespace
}  // namespace raycube::node
