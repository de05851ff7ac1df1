// Priol & Bouatouch 3.7.2: the objects a processor's light rays may meet, found by the host (light cones,
// figure 12; light pyramids, figure 13). Conservative: every object a light ray from the sources to the
// light meets is in the volume; and the volume prunes: objects well away from every such ray are not.
#include "host/prepare/light_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/tolerances.h"
#include "core/whitted.h"

namespace raycube::host {
namespace {

using core::Box;
using core::Vec3;

// Whether the segment from a to b meets the box (slab test on [0, 1]).
bool segmentMeets(const Box& box, const Vec3& a, const Vec3& b) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    if (d == 0) {
      if (a[k] < box.lo[k] || a[k] > box.hi[k]) return false;
      continue;
    }
    double ta = (box.lo[k] - a[k]) / d, tb = (box.hi[k] - a[k]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

// The shape of a BVH over spheres at the boxes' centres (any tree over the same objects answers the same).
core::BvhShape shapeOver(const std::vector<Box>& boxes) {
  core::Scene scene;
  scene.materials.push_back(core::Material{});
  for (const Box& b : boxes) scene.objects.push_back(core::Object{core::Sphere{b.center(), 1.0}});
  const core::Whitted shading(scene, core::ShadingOptions{});
  return core::Bvh(scene, shading).shape();
}

// Sources: the world box [lo, lo + size]; its eye box only needs to be non-empty here.
node::LightSources sourcesIn(const Vec3& lo, const Vec3& size) {
  node::LightSources sources;
  sources.eyeBox = Box{Vec3(0), Vec3(1)};
  for (int c = 0; c < 8; ++c)
    sources.corners.push_back(lo + Vec3(c & 1 ? size.x : 0, c & 2 ? size.y : 0, c & 4 ? size.z : 0));
  return sources;
}

TEST(LightVolume, HoldsEveryObjectALightRayMeetsAndPrunesTheRest) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(-50, 50), size(0, 3), unit(0, 1);
  std::uniform_real_distribution<double> near(-3, 3);
  const Vec3 light(80, -60, 90), sourceSize(4, 6, 3);
  const Vec3 sourceCorners[] = {Vec3(-10, 5, -20), Vec3(30, -40, 0), Vec3(-45, 40, -45)};
  // Boxes anywhere, and as many close to the light rays, across the volumes' faces.
  std::vector<Box> boxes;
  for (int i = 0; i < 6000; ++i) {
    Vec3 lo(at(rng), at(rng), at(rng));
    if (i % 2) {
      const Vec3 start = sourceCorners[i % 3] + Vec3(unit(rng), unit(rng), unit(rng)) * sourceSize;
      lo = start + unit(rng) * (light - start) + Vec3(near(rng), near(rng), near(rng));
    }
    boxes.push_back(Box{lo, lo + Vec3(size(rng), size(rng), size(rng))});
  }
  const BoxTree tree(boxes, shapeOver(boxes));
  for (const Vec3& sourceLo : sourceCorners) {
    const node::LightSources sources = sourcesIn(sourceLo, sourceSize);
    for (node::LightRayMode mode : {node::LightRayMode::Pyramid, node::LightRayMode::Cone}) {
      const std::vector<std::uint32_t> volume = objectsInLightVolume(mode, light, sources, tree);
      ASSERT_TRUE(std::is_sorted(volume.begin(), volume.end()));
      auto inVolume = [&](std::uint32_t o) { return std::binary_search(volume.begin(), volume.end(), o); };
      // Light rays from points of the sources, the corners and faces among them.
      std::size_t met = 0;
      for (int ray = 0; ray < 2000; ++ray) {
        Vec3 start = sourceLo + Vec3(unit(rng), unit(rng), unit(rng)) * sourceSize;
        if (ray < 8) start = sources.corners[std::size_t(ray)];
        for (std::uint32_t o = 0; o < boxes.size(); ++o)
          if (segmentMeets(boxes[o], start, light)) {
            ++met;
            ASSERT_TRUE(inVolume(o)) << "object " << o << " on a light ray is missing (mode " << int(mode)
                                     << ")";
          }
      }
      EXPECT_GT(met, 0u);
      // Pruned: far fewer objects than the scene; none lying behind the light.
      EXPECT_LT(volume.size(), boxes.size() / 3);
      const Vec3 towardSources = glm::normalize(sourceLo + 0.5 * sourceSize - light);
      for (std::uint32_t o : volume) {
        const Box& b = boxes[o];
        double ahead = -core::kInfinity;  // the box's farthest reach from the light towards the sources
        for (int c = 0; c < 8; ++c)
          ahead = std::max(ahead, glm::dot(Vec3(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y,
                                                c & 4 ? b.hi.z : b.lo.z) -
                                               light,
                                           towardSources));
        // (a cone keeps a bounding sphere reaching past the light)
        EXPECT_GE(ahead, -glm::length(b.extent())) << "object " << o << " lies behind the light";
      }
    }
  }
}

// A box inside the pyramid is taken whole; one touching the light's apex or straddling a face is tested
// object by object: either way the same objects (the tree's subtrees inside are only a shortcut).
TEST(LightVolume, PyramidFindsWhatTestingEveryObjectFinds) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> along(0.05, 0.95), jitter(-2, 2), size(0, 0.5);
  const Vec3 light(0, 0, 100), sourceLo(-5, -5, 0), sourceSize(10, 10, 1);
  std::vector<Box> boxes;
  for (int i = 0; i < 2000; ++i) {  // clustered along the pyramid, many inside, many across its faces
    const Vec3 centre = light + along(rng) * (Vec3(0, 0, 0.5) - light) + Vec3(jitter(rng), jitter(rng), 0);
    boxes.push_back(Box{centre, centre + Vec3(size(rng), size(rng), size(rng))});
  }
  const node::LightSources sources = sourcesIn(sourceLo, sourceSize);
  const std::vector<std::uint32_t> whole =
      objectsInLightVolume(node::LightRayMode::Pyramid, light, sources, BoxTree(boxes, shapeOver(boxes)));
  // The same boxes, each its own tree: no subtree to take whole.
  std::vector<std::uint32_t> oneByOne;
  for (std::uint32_t o = 0; o < boxes.size(); ++o) {
    const std::vector<Box> single{boxes[o]};
    if (!objectsInLightVolume(node::LightRayMode::Pyramid, light, sources, BoxTree(single, shapeOver(single)))
             .empty())
      oneByOne.push_back(o);
  }
  EXPECT_EQ(whole, oneByOne);
  EXPECT_GT(whole.size(), boxes.size() / 4);
  EXPECT_LT(whole.size(), boxes.size());
}

}  // namespace
}  // namespace raycube::host
