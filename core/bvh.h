#pragma once
// Bounding volume hierarchy for the image-parallel baseline (the "Roth" machine: whole database in every
// worker). Its answers equal BruteForce's bit for bit: same intersection functions, same tie rule. Its boxes
// and slab tests are in the precision Real of the rays it answers.
#include <cstdint>
#include <vector>

#include "core/box.h"
#include "core/intersect.h"
#include "core/trace_stats.h"
#include "core/whitted.h"

namespace raycube::core {

template <class Real>
class BasicBvh {
 public:
  BasicBvh(const Scene& scene, const Whitted& shading);
  // Over a subset of the scene's objects (indices), e.g. what a processor holds.
  BasicBvh(const Scene& scene, const Whitted& shading, std::vector<std::uint32_t> objects);

  Hit closestHit(const BasicRay<Real>& ray, TraceCounters& counters) const;
  double transmission(const BasicRay<Real>& ray, TraceCounters& counters, std::vector<Hit>& crossed) const;
  std::size_t nodeCount() const { return nodes_.size(); }

 private:
  struct Node {
    BasicBox<Real> box;
    std::uint32_t first = 0;  // leaf: first index into order_; inner: index of the right child
    std::uint32_t count = 0;  // leaf: number of objects; inner: 0 (left child follows the node)
    std::uint8_t axis = 0;
  };
  std::uint32_t build(std::vector<Box>& boxes, std::uint32_t begin, std::uint32_t end, int depth);
  template <class Visit>
  void traverse(const BasicRay<Real>& ray, const Real& tLimit, TraceCounters& counters, Visit&& visit) const;

  const Scene& scene_;
  const Whitted& shading_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;  // object indices, leaves point into it
};
using Bvh = BasicBvh<double>;

}  // namespace raycube::core
