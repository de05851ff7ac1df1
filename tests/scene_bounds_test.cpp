// Where the scene lies (node/scene_bounds.h): the last t at which a ray is inside one of the boxes, from a
// given t on, or none when it meets none of them there.
#include "node/scene_bounds.h"

#include <gtest/gtest.h>

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

// A ray along a box's face, or parallel to a slab it lies in, is inside (the slab test's NaNs leave that
// slab unconstrained): conservative, never a ray ended that could touch a box.
TEST(SceneBounds, RaysGrazingABoxCountAsInside) {
  EXPECT_TRUE(lastInsideBounds(kTwoBoxes, core::Vec3(0, 1, 0), core::Vec3(1, 0, 0), 0, core::kInfinity));
  EXPECT_TRUE(lastInsideBounds(kTwoBoxes, core::Vec3(1, 0, 0), core::Vec3(0, 0, 1), 0, core::kInfinity));
}

}  // namespace
}  // namespace raycube::node
