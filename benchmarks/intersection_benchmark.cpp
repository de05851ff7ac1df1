// The intersection kernels every renderer and every node runs: one ray against one primitive
// (core::nearestHit), a ray against the whole balls2 database through the BVH (closest hit and the light
// ray's transmission query), and a ray against one of SPD gears' 144-vertex concave faces, as the fan of
// triangles the polygons were tested as before and as the banded outline they are tested as now. items/s is
// rays per second. Also building the BVH over SPD scenes at their default sizes (items/s: objects).
//
//   intersection_benchmark --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "core/bvh.h"
#include "core/intersect.h"
#include "core/nff_reader.h"
#include "core/polygon_outline.h"
#include "core/spd/balls.h"
#include "core/spd/generators.h"
#include "core/whitted.h"
#include "host/prepare/box_tree.h"

namespace raycube::core {
namespace {

constexpr int kRays = 4096;  // enough distinct rays to defeat branch prediction, few enough to stay in L1/L2

Vec3 randomUnit(std::mt19937_64& random) {
  std::normal_distribution<double> normal;
  return glm::normalize(Vec3(normal(random), normal(random), normal(random)));
}

// Rays from random points on a sphere of radius 3 about the origin towards random points in a ball of
// radius `aim` about the origin: with aim below the primitive's size most rays hit, well above most miss.
std::vector<Ray> raysTowardsOrigin(double aim, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::vector<Ray> rays(kRays);
  for (Ray& ray : rays) {
    ray.origin = 3.0 * randomUnit(random);
    const Vec3 target = aim * std::cbrt(uniform(random)) * randomUnit(random);
    ray.direction = glm::normalize(target - ray.origin);
    ray.tMin = 0;
    ray.tMax = kInfinity;
  }
  return rays;
}

void runNearestHit(benchmark::State& state, const Object& object, const std::vector<Ray>& rays) {
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    const Ray& ray = rays[i];
    i = (i + 1) & (kRays - 1);
    const double t = nearestHit(object, ray, kInfinity);
    hits += t < kInfinity;
    benchmark::DoNotOptimize(t);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["hit_fraction"] = state.iterations() > 0 ? double(hits) / double(state.iterations()) : 0.0;
}

void BM_NearestHit_SphereHit(benchmark::State& state) {
  const Object sphere{Sphere{Vec3(0), 1.0}, 0, false};
  runNearestHit(state, sphere, raysTowardsOrigin(0.5, 1));
}

void BM_NearestHit_SphereMiss(benchmark::State& state) {
  // Every ray aims at a point beyond the sphere's reach from its direction: a miss with a real discriminant
  // test.
  const Object sphere{Sphere{Vec3(0, 0, 0), 0.1}, 0, false};
  std::vector<Ray> rays = raysTowardsOrigin(0.0, 2);
  for (Ray& ray : rays) ray.origin += 0.5 * glm::normalize(glm::cross(ray.direction, Vec3(0.3, 0.5, 0.8)));
  runNearestHit(state, sphere, rays);
}

void BM_NearestHit_Quad(benchmark::State& state) {
  const Object quad{Polygon{{Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)}}, 0, false};
  runNearestHit(state, quad, raysTowardsOrigin(1.0, 3));
}

void BM_NearestHit_PatchTriangle(benchmark::State& state) {
  const Object patch{
      Patch{{Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)},
            {glm::normalize(Vec3(-0.2, -0.2, 1)), glm::normalize(Vec3(0.2, -0.2, 1)), Vec3(0, 0, 1)}},
      0, false};
  runNearestHit(state, patch, raysTowardsOrigin(1.0, 4));
}

void BM_NearestHit_Cone(benchmark::State& state) {
  const Object cone{Cone{Vec3(0, 0, -1), 0.6, Vec3(0, 0, 1), 0.2}, 0, false};
  runNearestHit(state, cone, raysTowardsOrigin(1.0, 5));
}

// The first gear face of scenes/gears4.nff (144 vertices, 36 teeth), and rays from 3 face-widths above it
// towards random points of its bounding box: about half of them meet the face, the rest pass between teeth
// or beside the gear.
struct GearFace {
  std::vector<Vec3> vertices;
  std::vector<Ray> rays;
};
const GearFace& gearFace() {
  static const GearFace face = [] {
    GearFace f;
    for (const Object& object : readNff(RAYCUBE_SOURCE_DIR "/scenes/gears4.nff").objects)
      if (const auto* p = std::get_if<Polygon>(&object.shape); p && p->outline) {
        f.vertices = p->vertices.toVector();
        break;
      }
    Box box;
    for (const Vec3& v : f.vertices) box.extend(v);
    const Vec3 normal = PolygonOutline(f.vertices).normal();
    const double width = std::max({box.extent().x, box.extent().y, box.extent().z});
    std::mt19937_64 random(8);
    std::uniform_real_distribution<double> uniform(0, 1);
    for (int i = 0; i < kRays; ++i) {
      const Vec3 target = box.lo + Vec3(uniform(random), uniform(random), uniform(random)) * box.extent();
      const Vec3 origin = box.center() + 3 * width * normal + width * (randomUnit(random) * 0.5);
      f.rays.push_back(Ray{origin, glm::normalize(target - origin), 0, kInfinity});
    }
    return f;
  }();
  return face;
}

// Before: the polygon as the fan of triangles around vertex 0 (a patch is still tested that way).
void BM_NearestHit_GearFace_Fan(benchmark::State& state) {
  const GearFace& face = gearFace();
  const Object fan{Patch{face.vertices, std::vector<Vec3>(face.vertices.size(), Vec3(0, 0, 1))}, 0, false};
  runNearestHit(state, fan, face.rays);
}

// Now: the banded outline.
void BM_NearestHit_GearFace_Outline(benchmark::State& state) {
  const GearFace& face = gearFace();
  runNearestHit(state, Object{Polygon(face.vertices), 0, false}, face.rays);
}

// A regular convex polygon of `vertices` corners (radius 1, plane z = 0), and rays towards it from a ball of
// radius 3 about the origin: where the fan of triangles stops paying against the banded outline.
std::vector<Vec3> regularPolygon(int vertices) {
  std::vector<Vec3> corners;
  for (int k = 0; k < vertices; ++k) {
    const double angle = 2 * 3.14159265358979323846 * k / vertices;
    corners.emplace_back(std::cos(angle), std::sin(angle), 0.0);
  }
  return corners;
}

void BM_NearestHit_ConvexPolygon_Fan(benchmark::State& state) {
  const std::vector<Vec3> corners = regularPolygon(int(state.range(0)));
  const Object fan{Patch{corners, std::vector<Vec3>(corners.size(), Vec3(0, 0, 1))}, 0, false};
  runNearestHit(state, fan, raysTowardsOrigin(1.0, 11));
}

void BM_NearestHit_ConvexPolygon_Outline(benchmark::State& state) {
  const std::vector<Vec3> corners = regularPolygon(int(state.range(0)));
  Polygon polygon(corners);
  polygon.outline = std::make_shared<const PolygonOutline>(corners);
  runNearestHit(state, Object{polygon, 0, false}, raysTowardsOrigin(1.0, 11));
}

// As a scene holds it: the fan up to kMostFanVertices corners, the outline beyond.
void BM_NearestHit_ConvexPolygon(benchmark::State& state) {
  runNearestHit(state, Object{Polygon(regularPolygon(int(state.range(0)))), 0, false},
                raysTowardsOrigin(1.0, 11));
}

BENCHMARK(BM_NearestHit_SphereHit);
BENCHMARK(BM_NearestHit_SphereMiss);
BENCHMARK(BM_NearestHit_Quad);
BENCHMARK(BM_NearestHit_PatchTriangle);
BENCHMARK(BM_NearestHit_Cone);
BENCHMARK(BM_NearestHit_GearFace_Fan);
BENCHMARK(BM_NearestHit_GearFace_Outline);
BENCHMARK(BM_NearestHit_ConvexPolygon_Fan)->RangeMultiplier(2)->Range(3, 128);
BENCHMARK(BM_NearestHit_ConvexPolygon_Outline)->RangeMultiplier(2)->Range(3, 128);
BENCHMARK(BM_NearestHit_ConvexPolygon)->RangeMultiplier(2)->Range(3, 128);

// balls2 (91 spheres and the floor) and its BVH, built once.
struct Balls2 {
  Scene scene = makeBalls(2);
  Whitted shading{scene, ShadingOptions{}};
  Bvh bvh{scene, shading};
};
const Balls2& balls2() {
  static const Balls2 instance;
  return instance;
}

// Random rays through the flake's neighbourhood: from the camera region towards the flake, as eye and
// reflected rays go.
std::vector<Ray> randomSceneRays(std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> uniform(-0.8, 0.8);
  std::vector<Ray> rays(kRays);
  for (Ray& ray : rays) {
    ray.origin = Vec3(2.1, 1.3, 1.7) + 0.5 * Vec3(uniform(random), uniform(random), uniform(random));
    ray.direction =
        glm::normalize(Vec3(uniform(random), uniform(random), uniform(random) - 0.2) - ray.origin);
    ray.tMin = 0;
    ray.tMax = kInfinity;
  }
  return rays;
}

void BM_BvhClosestHit_Balls2(benchmark::State& state) {
  const Balls2& b = balls2();
  const std::vector<Ray> rays = randomSceneRays(6);
  TraceCounters counters;
  std::size_t i = 0;
  for (auto _ : state) {
    const Hit hit = b.bvh.closestHit(rays[i], counters);
    i = (i + 1) & (kRays - 1);
    benchmark::DoNotOptimize(hit);
  }
  state.SetItemsProcessed(state.iterations());
  const double n = double(state.iterations());
  state.counters["object_tests_per_ray"] = n > 0 ? double(counters.intersectionTests) / n : 0.0;
  state.counters["box_tests_per_ray"] = n > 0 ? double(counters.boxTests) / n : 0.0;
}

// Light rays: from the points the random rays hit, towards the first light, as Whitted spawns them.
void BM_BvhTransmission_Balls2(benchmark::State& state) {
  const Balls2& b = balls2();
  std::vector<Ray> shadows;
  TraceCounters scratchCounters;
  for (const Ray& ray : randomSceneRays(7)) {
    const Hit hit = b.bvh.closestHit(ray, scratchCounters);
    if (!hit.found()) continue;
    const SurfacePoint sp = surfaceAt(b.scene.objects[hit.object], ray, hit.t);
    const Vec3 n = glm::dot(sp.geometricNormal, ray.direction) < 0 ? sp.geometricNormal : -sp.geometricNormal;
    Ray shadow;
    shadow.origin = spawnOrigin(sp.point, n, hit.t);
    const Vec3 toLight = b.scene.lights[0].position - shadow.origin;
    shadow.tMax = glm::length(toLight);
    shadow.direction = toLight / shadow.tMax;
    shadow.tMin = 0;
    shadows.push_back(shadow);
  }
  if (shadows.empty()) {
    state.SkipWithError("no random ray hit balls2");
    return;
  }
  TraceCounters counters;
  std::vector<Hit> crossed;
  std::size_t i = 0, lit = 0;
  for (auto _ : state) {
    const double t = b.bvh.transmission(shadows[i], counters, crossed);
    lit += t > 0;
    i = i + 1 == shadows.size() ? 0 : i + 1;
    benchmark::DoNotOptimize(t);
  }
  state.SetItemsProcessed(state.iterations());
  const double n = double(state.iterations());
  state.counters["lit_fraction"] = n > 0 ? double(lit) / n : 0.0;
  state.counters["object_tests_per_ray"] = n > 0 ? double(counters.intersectionTests) / n : 0.0;
}

BENCHMARK(BM_BvhClosestHit_Balls2);
BENCHMARK(BM_BvhTransmission_Balls2);

// Building the BVH over an SPD scene at its default size (the machine builds one per distinct database and
// one per dense region: a preprocessing cost). items/s is objects per second.
void BM_BvhBuild(benchmark::State& state, const char* name, Bvh::BuildOn on) {
  const Scene scene = makeSpdScene(name);
  const Whitted shading(scene, ShadingOptions{});
  for (auto _ : state) {
    const Bvh bvh(scene, shading, on);
    benchmark::DoNotOptimize(bvh.nodeCount());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(scene.objects.size()));
}
BENCHMARK_CAPTURE(BM_BvhBuild, sombrero3, "sombrero", Bvh::BuildOn::OneCore)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BvhBuild, balls4, "balls", Bvh::BuildOn::OneCore)->Unit(benchmark::kMillisecond);
// On every core, as the host builds its trees over the whole scene: wall time is what counts.
BENCHMARK_CAPTURE(BM_BvhBuild, sombrero3_every_core, "sombrero", Bvh::BuildOn::EveryCore)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_BvhBuild, balls4_every_core, "balls", Bvh::BuildOn::EveryCore)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A processor's BVHs keep the shape of the host's tree over the whole scene, restricted to what the
// processor holds (every `stride`-th object: 2 as a dense region, 16 as scattered light-volume objects, 64
// as one region's of 64), in
// place (the whole scene's own indices), with leaves of up to `largestLeaf` objects: the cost per processor
// and database. items/s: objects kept.
void BM_BvhRestrict(benchmark::State& state, const char* name, std::uint32_t stride,
                    std::uint32_t largestLeaf) {
  const Scene scene = makeSpdScene(name);
  const Whitted shading(scene, ShadingOptions{});
  const BvhShape whole = Bvh(scene, shading).shape();
  std::vector<std::uint32_t> held;
  for (std::uint32_t o = 0; o < scene.objects.size(); o += stride) held.push_back(o);
  for (auto _ : state) {
    const Bvh bvh(scene, shading, held, whole, {}, largestLeaf);
    benchmark::DoNotOptimize(bvh.nodeCount());
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(held.size()));
}
BENCHMARK_CAPTURE(BM_BvhRestrict, sombrero3_half_leaf1, "sombrero", 2, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BvhRestrict, sombrero3_sixteenth_leaf2, "sombrero", 16, 2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BvhRestrict, sombrero3_sixtyfourth_leaf1, "sombrero", 64, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BvhRestrict, balls4_half_leaf1, "balls", 2, 1)->Unit(benchmark::kMillisecond);

// The host's pruning box tree over every object's world box, of the sampling BVH's shape (made twice per
// machine run: world and eye-frame boxes), and where the scene lies (4 boxes of median splits). items/s:
// objects.
std::vector<Box> worldBoxesOf(const Scene& scene) {
  std::vector<Box> boxes;
  for (const Object& o : scene.objects) boxes.push_back(boundsOf(o, 0));
  return boxes;
}
void BM_BoxTreeOfBvhShape(benchmark::State& state, const char* name) {
  const Scene scene = makeSpdScene(name);
  const Whitted shading(scene, ShadingOptions{});
  const BvhShape shape = Bvh(scene, shading).shape();
  const std::vector<Box> boxes = worldBoxesOf(scene);
  for (auto _ : state) {
    const host::BoxTree tree(boxes, shape);
    benchmark::DoNotOptimize(&tree);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(boxes.size()));
}
BENCHMARK_CAPTURE(BM_BoxTreeOfBvhShape, sombrero3, "sombrero")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BoxTreeOfBvhShape, balls4, "balls")->Unit(benchmark::kMillisecond);
void BM_MedianCover(benchmark::State& state, const char* name) {
  const std::vector<Box> boxes = worldBoxesOf(makeSpdScene(name));
  for (auto _ : state) benchmark::DoNotOptimize(host::medianCover(boxes, 4));
  state.SetItemsProcessed(state.iterations() * std::int64_t(boxes.size()));
}
BENCHMARK_CAPTURE(BM_MedianCover, sombrero3, "sombrero")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MedianCover, balls4, "balls")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace raycube::core

BENCHMARK_MAIN();
