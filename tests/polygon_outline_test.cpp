// Concave polygons (SPD gears' 144-vertex faces): the banded outline answers exactly as the even-odd
// crossing test over every edge, on random points and on the hard ones (vertices, edges, a rounding step
// either side of them, the heights of vertices); a ray through a notch misses; convex polygons keep the fan.
#include "core/polygon_outline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "core/intersect.h"
#include "core/scene.h"

namespace raycube::core {
namespace {

// The rule the outline implements, over every edge, written plainly: a half-line from (x, y) towards +x
// crosses an edge (taken lower end first) when y0 <= y < y1 and x is left of the edge at height y.
bool evenOddOverAllEdges(const std::vector<Vec3>& v, double x, double y) {
  bool inside = false;
  for (std::size_t i = 0; i < v.size(); ++i) {
    Vec3 a = v[i], b = v[(i + 1) % v.size()];
    if (a.y == b.y) continue;
    if (a.y > b.y) std::swap(a, b);
    const double slope = (b.x - a.x) / (b.y - a.y);
    if (a.y <= y && y < b.y && x < a.x + (y - a.y) * slope) inside = !inside;
  }
  return inside;
}

// A star of `points` tips in the plane z = 0: tips at radius 1, notches at `inner`.
std::vector<Vec3> star(int points, double inner) {
  std::vector<Vec3> v;
  for (int i = 0; i < 2 * points; ++i) {
    const double angle = std::numbers::pi * i / points, r = i % 2 == 0 ? 1.0 : inner;
    v.emplace_back(r * std::cos(angle), r * std::sin(angle), 0);
  }
  return v;
}

// A comb in z = 0: a spine along y = 0..0.2, `teeth` teeth of width 0.5/teeth up to y = 1, gaps between.
std::vector<Vec3> comb(int teeth) {
  std::vector<Vec3> v{{1, 0, 0}, {1, 0.2, 0}};
  const double pitch = 1.0 / teeth;
  for (int i = teeth - 1; i >= 0; --i) {
    const double left = i * pitch, right = left + pitch / 2;
    v.emplace_back(right, 0.2, 0);
    v.emplace_back(right, 1, 0);
    v.emplace_back(left, 1, 0);
    v.emplace_back(left, 0.2, 0);
  }
  v.emplace_back(0, 0, 0);
  return v;
}

// A column whose right side zigzags between x = 1 and 2, one unit of height per edge, and whose left side
// has a vertex at every unit too: 2 * rows edges can be crossed over a height of rows, so the outline's
// band boundaries fall on the vertices' heights, where a band lookup off by one would show.
std::vector<Vec3> zigzag(int rows) {
  std::vector<Vec3> v;
  for (int k = 0; k <= rows; ++k) v.emplace_back(k % 2 == 0 ? 1 : 2, k, 0);
  for (int k = rows; k >= 0; --k) v.emplace_back(0, k, 0);
  return v;
}

// The points where a banded test could go wrong: every vertex, every edge's midpoint and its point at every
// vertex height, and each of those moved by one rounding step in x and in y.
std::vector<Vec3> hardPoints(const std::vector<Vec3>& v) {
  std::vector<Vec3> on;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3 a = v[i], b = v[(i + 1) % v.size()];
    on.push_back(a);
    on.push_back(0.5 * (a + b));
    for (const Vec3& level : v)
      if ((a.y - level.y) * (b.y - level.y) < 0)
        on.emplace_back(a.x + (level.y - a.y) * (b.x - a.x) / (b.y - a.y), level.y, 0);
  }
  std::vector<Vec3> points;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const Vec3& p : on)
    for (double x : {std::nextafter(p.x, -kInf), p.x, std::nextafter(p.x, kInf)})
      for (double y : {std::nextafter(p.y, -kInf), p.y, std::nextafter(p.y, kInf)}) points.emplace_back(x, y, 0);
  return points;
}

std::vector<Vec3> randomPoints(std::size_t count, double lo, double hi, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(lo, hi);
  std::vector<Vec3> points(count);
  for (Vec3& p : points) p = Vec3(uniform(random), uniform(random), 0);
  return points;
}

void expectSameAsEveryEdge(const std::vector<Vec3>& polygon, const std::vector<Vec3>& points) {
  const PolygonOutline outline(polygon);
  std::size_t inside = 0;
  for (const Vec3& p : points) {
    const bool expected = evenOddOverAllEdges(polygon, p.x, p.y);
    ASSERT_EQ(outline.contains(p), expected) << "at (" << p.x << ", " << p.y << ")";
    inside += expected;
  }
  EXPECT_GT(inside, 0u);
  EXPECT_LT(inside, points.size());
}

TEST(PolygonOutline, StarAnswersAsTheCrossingTestOverEveryEdge) {
  const std::vector<Vec3> s = star(7, 0.4);
  expectSameAsEveryEdge(s, randomPoints(20000, -1.1, 1.1, 1));
  expectSameAsEveryEdge(s, hardPoints(s));
}

TEST(PolygonOutline, CombAnswersAsTheCrossingTestOverEveryEdge) {
  const std::vector<Vec3> c = comb(36);  // 146 vertices, as many as a gear face
  expectSameAsEveryEdge(c, randomPoints(20000, -0.1, 1.1, 2));
  expectSameAsEveryEdge(c, hardPoints(c));
}

TEST(PolygonOutline, ZigzagWithVerticesOnBandBoundariesAnswersAsTheCrossingTest) {
  const std::vector<Vec3> z = zigzag(40);
  ASSERT_EQ(PolygonOutline(z).bandCount(), 80u);
  expectSameAsEveryEdge(z, randomPoints(20000, -0.5, 40.5, 3));
  expectSameAsEveryEdge(z, hardPoints(z));
}

TEST(PolygonOutline, NotchesAreOutsideAndTheBodyInside) {
  const PolygonOutline s(star(5, 0.4));
  EXPECT_TRUE(s.contains(Vec3(0, 0, 0)));
  EXPECT_TRUE(s.contains(Vec3(0.9, 0, 0)));  // in a tip
  // Between two tips, beyond the notch radius: the fan around vertex 0 would cover it.
  const double between = std::numbers::pi / 5;
  EXPECT_FALSE(s.contains(Vec3(0.7 * std::cos(between), 0.7 * std::sin(between), 0)));
  const PolygonOutline c(comb(10));
  EXPECT_TRUE(c.contains(Vec3(0.02, 0.9, 0)));   // in the first tooth
  EXPECT_FALSE(c.contains(Vec3(0.07, 0.9, 0)));  // in the gap after it
  EXPECT_TRUE(c.contains(Vec3(0.07, 0.1, 0)));   // in the spine
}

TEST(PolygonOutline, BandsHoldAFewEdgesEach) {
  const PolygonOutline c(comb(36));
  std::size_t most = 0;
  for (std::size_t b = 0; b < c.bandCount(); ++b) most = std::max(most, c.edgesInBand(b));
  EXPECT_GE(c.bandCount(), 36u);
  EXPECT_LE(most, 74u);  // the teeth's flanks all span the band at the teeth's height: not fewer than 72
}

// Two coplanar concave polygons sharing an edge: a point of the shared edge is in exactly one of them.
TEST(PolygonOutline, ASharedEdgeBelongsToExactlyOneSide) {
  const std::vector<Vec3> left{{0, 0, 0}, {1, 0.1, 0}, {1.3, 1.7, 0}, {0.5, 1, 0}, {0, 2, 0}};
  const std::vector<Vec3> right{{1, 0.1, 0}, {2, 0, 0}, {2, 2, 0}, {1.6, 1, 0}, {1.3, 1.7, 0}};
  const PolygonOutline l(left), r(right);
  for (int i = 1; i < 1000; ++i) {
    const double s = i / 1000.0;
    const Vec3 p = (1 - s) * Vec3(1, 0.1, 0) + s * Vec3(1.3, 1.7, 0);
    EXPECT_NE(l.contains(p), r.contains(p)) << "at s = " << s;
  }
}

// A triangle is its own fan; every polygon of more corners, convex or not, is tested on its outline.
TEST(PolygonOutline, CornerCountDecidesWhichTestAPolygonGets) {
  EXPECT_EQ(Polygon({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}).outline, nullptr);
  EXPECT_NE(Polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}).outline, nullptr);
  EXPECT_NE(Polygon(star(5, 0.4)).outline, nullptr);
}

// In a tilted plane (dropped axis x), through nearestHit: a ray through a notch misses, one through the body
// meets the plane where it should, in double and in float.
TEST(PolygonOutline, RaysThroughNotchesMissAndThroughTheBodyHit) {
  std::vector<Vec3> tilted;  // the star in the plane x = 5 + z/4, seen along x
  for (const Vec3& p : star(6, 0.3)) tilted.emplace_back(5 + 0.25 * p.y, p.x, p.y);
  const Object object{Polygon(tilted), 0, false};
  ASSERT_NE(std::get<Polygon>(object.shape).outline, nullptr);
  const Vec3 origin(-3, 0.1, 0.2);
  const Vec3 body(5, 0.2, 0);                          // within the notches' radius
  const Vec3 notch = 0.5 * (tilted[0] + tilted[2]);  // on the chord between two tips: outside
  const auto rayTo = [&](const Vec3& target) { return Ray{origin, glm::normalize(target - origin), 0, kInfinity}; };
  constexpr float kFloatNone = std::numeric_limits<float>::infinity();

  const Ray hitting = rayTo(body);
  const double t = nearestHit(object, hitting, kInfinity);
  EXPECT_NEAR(t, glm::length(body - origin), 1e-12);
  EXPECT_NEAR(nearestHit(object, hitting.as<float>(), kFloatNone), t, 1e-5);
  EXPECT_EQ(nearestHit(object, hitting, t / 2), kInfinity);  // beyond tMax

  const Ray missing = rayTo(notch);
  EXPECT_EQ(nearestHit(object, missing, kInfinity), kInfinity);
  EXPECT_EQ(nearestHit(object, missing.as<float>(), kFloatNone), kFloatNone);
}

TEST(PolygonOutline, ScalingAPolygonRebuildsItsOutline) {
  Scene scene;
  scene.materials.push_back(Material{});
  scene.objects.push_back(Object{Polygon(star(5, 0.4)), 0, false});
  const Scene twice = scaledBy(scene, 2);
  const Polygon& p = std::get<Polygon>(twice.objects[0].shape);
  ASSERT_NE(p.outline, nullptr);
  EXPECT_TRUE(p.outline->contains(Vec3(1.8, 0, 0)));   // in the scaled tip
  EXPECT_FALSE(p.outline->contains(Vec3(2.2, 0, 0)));  // past it
}

}  // namespace
}  // namespace raycube::core
