// The BVH (core/bvh.h), built anew and kept from a whole scene's shape: a tree over part of a scene (its
// copy, or the whole scene's objects in place) restricted from the whole scene's tree answers every ray as
// one built over that part does, and as testing every object does, in both precisions.
#include "core/bvh.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "core/brute_force.h"
#include "core/spd/generators.h"

namespace raycube::core {
namespace {

// The objects `ids` of `whole` (ascending) as a scene of their own, with its materials and lights.
Scene partOf(const Scene& whole, const std::vector<std::uint32_t>& ids) {
  Scene part = whole;
  part.objects.clear();
  for (std::uint32_t id : ids) part.objects.push_back(whole.objects[id]);
  return part;
}

// Rays from anywhere in and around the scene towards its objects (near a random object's centre).
std::vector<Ray> raysThrough(const Scene& scene, int count, unsigned seed) {
  std::mt19937 random(seed);
  const double extent = scene.largestCoordinate();
  std::uniform_real_distribution<double> coordinate(-1.2 * extent, 1.2 * extent), jitter(-0.01, 0.01);
  std::uniform_int_distribution<std::size_t> object(0, scene.objects.size() - 1);
  std::vector<Ray> rays;
  while (int(rays.size()) < count) {
    const Vec3 from{coordinate(random), coordinate(random), coordinate(random)};
    const Vec3 to = boundsOf(scene.objects[object(random)], 0).center() +
                    extent * Vec3{jitter(random), jitter(random), jitter(random)};
    if (glm::length(to - from) < 1e-6 * extent) continue;
    rays.push_back(Ray{from, glm::normalize(to - from), 0, kInfinity});
  }
  return rays;
}

template <class Real>
void expectSameAnswers(const Scene& scene, const BasicBvh<Real>& kept, const BasicBvh<Real>& built,
                       const std::vector<std::uint32_t>& objects) {
  const Scene only = partOf(scene, objects);  // what a tree over `objects` may answer with
  const Whitted onlyShading(only, ShadingOptions{});
  const BruteForce brute(only, onlyShading);
  TraceCounters counters;
  int hits = 0, blocked = 0;
  std::vector<Hit> crossed;
  for (const Ray& r : raysThrough(scene, 3000, 11)) {
    const BasicRay<Real> ray = r.template as<Real>();

    const Hit a = kept.closestHit(ray, counters), b = built.closestHit(ray, counters);
    const Hit c = brute.closestHit(ray, counters);
    // As a light ray to a light beyond the first object in its way (or as far as the scene reaches): the
    // same objects block it.
    BasicRay<Real> lightRay = ray;
    lightRay.tMax = Real(c.found() ? 1.5 * c.t : scene.largestCoordinate());
    const double transmission = kept.transmission(lightRay, counters, crossed);
    ASSERT_EQ(transmission, built.transmission(lightRay, counters, crossed));
    blocked += transmission < 1;
    ASSERT_EQ(a.t, b.t);
    ASSERT_EQ(a.object, b.object);
    ASSERT_EQ(a.t, c.t);
    if (c.found()) {
      ASSERT_EQ(a.object, objects[c.object]);
      ++hits;
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(blocked, 100);
}

template <class Real>
void checkRestrictions() {
  const Scene whole = makeSpdScene("jacks", 3);
  const Whitted wholeShading(whole, ShadingOptions{});
  const BvhShape shape = Bvh(whole, wholeShading).shape();
  std::mt19937 random(5);
  for (double share : {0.05, 0.3, 1.0}) {
    // A processor's database: every share-th object of the whole scene, in ascending order.
    std::vector<std::uint32_t> held;
    for (std::uint32_t id = 0; id < whole.objects.size(); ++id)
      if (std::uniform_real_distribution<double>(0, 1)(random) < share) held.push_back(id);
    ASSERT_FALSE(held.empty());
    const Scene database = partOf(whole, held);
    const Whitted shading(database, ShadingOptions{});
    // Over all of it, and over half of it (the region's objects among what it holds).
    std::vector<std::uint32_t> all(held.size()), half;
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    for (std::uint32_t i = 0; i < all.size(); i += 2) half.push_back(i);
    for (const auto* objects : {&all, &half}) {
      const BasicBvh<Real> built(database, shading, *objects);
      const BasicBvh<Real> kept(database, shading, *objects, shape, held);
      EXPECT_LE(kept.nodeCount(), 2 * objects->size() - 1);  // single children lifted: a full binary tree
      expectSameAnswers(database, kept, built, *objects);
      // Scattered over the whole tree, a few objects in one branch share a leaf rather than a node each.
      const BasicBvh<Real> pairs(database, shading, *objects, shape, held, 2);
      if (share < 0.1) {
        EXPECT_LT(double(pairs.nodeCount()), 1.5 * double(objects->size()));
      }
      expectSameAnswers(database, pairs, built, *objects);
    }
    // Kept over the whole scene itself (no wholeIdOf: a database read in place, by global indices): the
    // copy's tree, node for node, naming the same objects.
    const BasicBvh<Real> inPlace(whole, wholeShading, held, shape, {}, 2);
    EXPECT_EQ(inPlace.nodeCount(), BasicBvh<Real>(database, shading, all, shape, held, 2).nodeCount());
    expectSameAnswers(whole, inPlace, BasicBvh<Real>(whole, wholeShading, held), held);
  }
}

TEST(Bvh, KeptFromTheWholeScenesShapeAnswersAsOneBuiltAnew) {
  checkRestrictions<double>();
}
TEST(Bvh, KeptFromTheWholeScenesShapeAnswersAsOneBuiltAnewInFloat) {
  checkRestrictions<float>();
}

// Built on every core (subtrees on threads of their own, joined in place), the tree is the one a build on
// one core makes: node for node, and box test for box test on every ray. Sombrero 3 (32,258 triangles) is
// large enough for threads on both spawning levels.
TEST(Bvh, BuiltOnEveryCoreIsTheTreeBuiltOnOne) {
  const Scene scene = makeSpdScene("sombrero");
  ASSERT_GT(scene.objects.size(), 4u * 4096);
  const Whitted shading(scene, ShadingOptions{});
  const Bvh one(scene, shading), every(scene, shading, Bvh::BuildOn::EveryCore);
  const BvhShape a = one.shape(), b = every.shape();
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t n = 0; n < a.nodes.size(); ++n) {
    ASSERT_EQ(a.nodes[n].first, b.nodes[n].first) << "node " << n;
    ASSERT_EQ(a.nodes[n].count, b.nodes[n].count) << "node " << n;
    ASSERT_EQ(a.nodes[n].axis, b.nodes[n].axis) << "node " << n;
  }
  EXPECT_EQ(a.order, b.order);
  TraceCounters countsOne, countsEvery;
  int hits = 0;
  for (const Ray& ray : raysThrough(scene, 2000, 17)) {
    const Hit h = one.closestHit(ray, countsOne), k = every.closestHit(ray, countsEvery);
    ASSERT_EQ(h.t, k.t);
    ASSERT_EQ(h.object, k.object);
    hits += h.found();
  }
  EXPECT_GT(hits, 100);
  EXPECT_EQ(countsOne.boxTests, countsEvery.boxTests);
  EXPECT_EQ(countsOne.intersectionTests, countsEvery.intersectionTests);
}

TEST(Bvh, KeptOverNothingIsEmpty) {
  const Scene whole = makeSpdScene("jacks", 1);
  const Whitted shading(whole, ShadingOptions{});
  const BvhShape shape = Bvh(whole, shading).shape();
  std::vector<std::uint32_t> ids(whole.objects.size());
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
  const Bvh kept(whole, shading, {}, shape, ids);
  EXPECT_EQ(kept.nodeCount(), 0u);
  TraceCounters counters;
  EXPECT_FALSE(kept.closestHit(raysThrough(whole, 1, 3).front(), counters).found());
}

TEST(Bvh, KeptLeavesHoldAtLeastOneObjectAndFewerThanACountCanSay) {
  const Scene whole = makeSpdScene("jacks", 1);
  const Whitted shading(whole, ShadingOptions{});
  const BvhShape shape = Bvh(whole, shading).shape();
  const std::vector<std::uint32_t> ids = everyObjectOf(whole);
  EXPECT_THROW(Bvh(whole, shading, ids, shape, ids, 0), std::invalid_argument);
  EXPECT_THROW(Bvh(whole, shading, ids, shape, ids, 255), std::invalid_argument);
  EXPECT_EQ(Bvh(whole, shading, ids, shape, ids, 254).nodeCount(), 1u);  // jacks 1: one leaf of all
}

}  // namespace
}  // namespace raycube::core
