#include "core/bvh.h"

#include <algorithm>

#include "core/transmission.h"

namespace raycube::core {

namespace {
constexpr std::uint32_t kLeafSize = 2;
}

Bvh::Bvh(const Scene& scene, const Whitted& shading) : scene_(scene), shading_(shading) {
  std::vector<Box> boxes;
  boxes.reserve(scene.objects.size());
  for (const Object& o : scene.objects) boxes.push_back(boundsOf(o));
  order_.resize(scene.objects.size());
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  nodes_.reserve(2 * order_.size() + 1);
  if (!order_.empty()) build(boxes, 0, std::uint32_t(order_.size()));
}

// Median split on the widest axis of the centroids.
std::uint32_t Bvh::build(std::vector<Box>& boxes, std::uint32_t begin, std::uint32_t end) {
  const std::uint32_t index = std::uint32_t(nodes_.size());
  nodes_.push_back(Node{});
  Box bounds, centroids;
  for (std::uint32_t i = begin; i < end; ++i) {
    bounds.extend(boxes[order_[i]]);
    centroids.extend(boxes[order_[i]].center());
  }
  nodes_[index].box = bounds;
  const Vec3 spread = centroids.extent();
  const int axis = spread.x > spread.y ? (spread.x > spread.z ? 0 : 2) : (spread.y > spread.z ? 1 : 2);
  if (end - begin <= kLeafSize || spread[axis] <= 0) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(
      order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
      [&](std::uint32_t a, std::uint32_t b) { return boxes[a].center()[axis] < boxes[b].center()[axis]; });
  build(boxes, begin, mid);
  const std::uint32_t right = build(boxes, mid, end);
  nodes_[index].first = right;
  nodes_[index].axis = std::uint8_t(axis);
  return index;
}

// Front-to-back traversal; a node is skipped only when it starts strictly beyond tLimit, so objects tied
// with the current best t are still visited and the tie rule can pick the smaller index.
template <class Visit>
void Bvh::traverse(const Ray& ray, const double& tLimit, TraceCounters& counters, Visit&& visit) const {
  if (nodes_.empty()) return;
  const InverseDirection inv(ray.direction);
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    ++counters.boxTests;
    double tEnter;
    if (!slabsHit(node.box, ray.origin, inv, ray.tMin, tLimit, tEnter)) continue;
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        if (!visit(order_[i])) return;
      continue;
    }
    const std::uint32_t left = std::uint32_t(&node - nodes_.data()) + 1;
    if (ray.direction[node.axis] < 0) {
      stack[top++] = left;
      stack[top++] = node.first;
    } else {
      stack[top++] = node.first;
      stack[top++] = left;
    }
  }
}

Hit Bvh::closestHit(const Ray& ray, TraceCounters& counters) const {
  Hit best;
  traverse(ray, best.t, counters, [&](std::uint32_t object) {
    ++counters.intersectionTests;
    const Hit h{nearestHit(scene_.objects[object], ray, kInfinity), object};
    if (h.t < kInfinity && h.closerThan(best)) best = h;
    return true;
  });
  return best;
}

double Bvh::transmission(const Ray& ray, TraceCounters& counters, std::vector<Hit>& crossed) const {
  crossed.clear();
  bool blocked = false;
  traverse(ray, ray.tMax, counters, [&](std::uint32_t object) {
    ++counters.intersectionTests;
    const double t = nearestHit(scene_.objects[object], ray, ray.tMax);
    if (t == kInfinity) return true;
    if (!shading_.transmissive(object)) {
      blocked = true;
      return false;  // an opaque object: no light, whatever else lies on the way
    }
    crossed.push_back(Hit{t, object});
    return true;
  });
  return blocked ? 0.0 : attenuate(1.0, crossed, shading_);
}

}  // namespace raycube::core
