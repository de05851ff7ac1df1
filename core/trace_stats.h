#pragma once
// Counters of tracing work, kept per thread or per processor and added up (SPD rule 12-13, Embree's
// per-kind counters). Plain integers: free when nobody reads them.
#include <array>
#include <cstdint>

#include "core/ray.h"

namespace raycube::core {

// Shapes in the order of core::Shape's alternatives (sphere, cone, polygon, patch).
inline constexpr std::size_t kShapeKinds = 4;

struct TraceCounters {
  std::array<std::uint64_t, kRayKinds> rays{};  // indexed by RayKind
  std::uint64_t intersectionTests = 0;          // ray-object tests
  std::array<std::uint64_t, kShapeKinds> testsByShape{};  // the same, by primitive kind (cost models)
  std::uint64_t polygonVerticesTested = 0;                // a polygon's test costs per vertex
  std::uint64_t boxTests = 0;                   // BVH nodes tested
  std::uint64_t cellSteps = 0;                  // the machine: cells entered (3.3) by a ray's walk
  std::uint64_t contributions = 0;              // pieces of pixel colour produced (section 3.4)
  std::uint64_t nonFinite = 0;                  // contributions with a NaN/Inf channel (a defect if > 0)

  std::uint64_t totalRays() const { return rays[0] + rays[1] + rays[2] + rays[3]; }
  std::uint64_t& of(RayKind kind) { return rays[std::size_t(kind)]; }
  std::uint64_t of(RayKind kind) const { return rays[std::size_t(kind)]; }
  TraceCounters& operator+=(const TraceCounters& o) {
    for (std::size_t i = 0; i < rays.size(); ++i) rays[i] += o.rays[i];
    intersectionTests += o.intersectionTests;
    for (std::size_t i = 0; i < testsByShape.size(); ++i) testsByShape[i] += o.testsByShape[i];
    polygonVerticesTested += o.polygonVerticesTested;
    boxTests += o.boxTests;
    cellSteps += o.cellSteps;
    contributions += o.contributions;
    nonFinite += o.nonFinite;
    return *this;
  }
};

const char* rayKindName(RayKind kind);

}  // namespace raycube::core
