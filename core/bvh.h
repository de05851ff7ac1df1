#pragma once
// Bounding volume hierarchy for the image-parallel baseline (the "Roth" machine: whole database in every
// worker). Its answers equal BruteForce's bit for bit: same intersection functions, same tie rule. Its boxes
// and slab tests are in the precision Real of the rays it answers.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/box.h"
#include "core/intersect.h"
#include "core/precision.h"
#include "core/trace_stats.h"
#include "core/transmission.h"
#include "core/whitted.h"

namespace raycube::core {

// The indices of all the scene's objects, in order.
std::vector<std::uint32_t> everyObjectOf(const Scene& scene);

// The shape of a BVH over a whole scene, without its boxes: a BVH over part of that scene can keep it,
// restricted to its own objects, instead of being built anew (a processor's trees, from the host's).
struct BvhShape {
  struct Node {
    std::uint32_t first = 0;  // as BasicBvh's nodes: leaf, first index into order; inner, the right child
    std::uint32_t count = 0;  // leaf: objects; inner: 0 (the left child follows the node)
    std::uint8_t axis = 0;
  };
  std::vector<Node> nodes;
  std::vector<std::uint32_t> order;   // object indices, leaves point into it
  std::vector<std::uint32_t> parent;  // per node (the root's is 0)
  std::vector<std::uint32_t> leafOf;  // per object of the scene: the leaf holding it
};

template <class Real>
class BasicBvh {
 public:
  // Where a build runs: on the calling thread, or on every core for the host's trees over a whole scene,
  // built while nothing else runs (subtrees of large nodes on threads of their own; the same tree).
  enum class BuildOn { OneCore, EveryCore };
  explicit BasicBvh(const Scene& scene, const Whitted& shading, BuildOn on = BuildOn::OneCore);
  // Over a subset of the scene's objects (indices), e.g. what a processor holds.
  BasicBvh(const Scene& scene, const Whitted& shading, std::vector<std::uint32_t> objects,
           BuildOn on = BuildOn::OneCore);
  // The same, shaped as `whole` (a BVH over a larger scene in which this scene's object i is object
  // wholeIdOf[i]; with wholeIdOf empty, `whole` is over this very scene) with the branches holding none of
  // `objects` cut off and single children lifted: a few nanoseconds per node kept, where a build bins every
  // object at every level. A branch holding at most largestLeaf (1-254) of the objects becomes one leaf:
  // objects scattered over the whole tree otherwise cost two nodes each. Its boxes are this tree's own, so
  // its answers are those of any BVH over them.
  BasicBvh(const Scene& scene, const Whitted& shading, const std::vector<std::uint32_t>& objects,
           const BvhShape& whole, std::span<const std::uint32_t> wholeIdOf, std::uint32_t largestLeaf = 1);

  BvhShape shape() const;

  Hit closestHit(const BasicRay<Real>& ray, TraceCounters& counters) const;
  double transmission(const BasicRay<Real>& ray, TraceCounters& counters, std::vector<Hit>& crossed) const;
  // The same over the objects held(object) accepts only: the others are passed over untested, as if absent.
  template <class Held>
  double transmission(const BasicRay<Real>& ray, TraceCounters& counters, std::vector<Hit>& crossed,
                      Held&& held) const;
  std::size_t nodeCount() const { return nodes_.size(); }
  // Front-to-back traversal: visit(object) for each object whose box the ray meets within [tFrom, tLimit],
  // until it returns false. tLimit is read again at every node, so visit may lower it (the best hit so far);
  // a node is skipped only when it starts strictly beyond tLimit, so objects tied with the current best t
  // are still visited and the tie rule can pick the smaller index.
  template <class Visit>
  void traverse(const BasicRay<Real>& ray, Real tFrom, const Real& tLimit, TraceCounters& counters,
                Visit&& visit) const;

 private:
  struct Node {
    BasicBox<Real> box;
    std::uint32_t first = 0;  // leaf: first index into order_; inner: index of the right child
    std::uint32_t count = 0;  // leaf: number of objects; inner: 0 (left child follows the node)
    std::uint8_t axis = 0;
  };
  // A traversal holds at most one pending sibling per level plus the node it visits, so bounding the depth
  // bounds its stack: degenerate scenes (each split peeling off one object) end in one larger leaf instead
  // of overflowing it.
  static constexpr int kMaxDepth = 60;
  static constexpr int kStackSize = kMaxDepth + 2;
  // An object as the build sees it, kept in build order so every pass reads memory in sequence.
  struct BuildItem {
    Box box;
    Vec3 centre;
    std::uint32_t object;
  };
  static constexpr int kBins = 16;
  // The surface-area heuristic's bins, per axis, reused from node to node: a node resets only the bins it
  // uses (one per object in small nodes), where fresh ones cost every node 48 boxes' worth of stores.
  struct Bins {
    Box boxes[3][kBins];
    std::uint32_t counts[3][kBins];
  };
  // Builds items [begin, end) into `nodes` (depth first: a node, its left subtree, its right subtree).
  // Above spawnLevels, a large node's right subtree builds on a thread of its own into nodes of its own,
  // appended once both are done: the layout of a build on one thread.
  std::uint32_t build(std::vector<BuildItem>& items, std::uint32_t begin, std::uint32_t end, int depth,
                      Bins& bins, std::vector<Node>& nodes, int spawnLevels);
  // The three axes binned in one pass over the boxes of items [begin, end) (each box read once).
  static void fillBins(const std::vector<BuildItem>& items, std::uint32_t begin, std::uint32_t end,
                       const Box& centroids, const Vec3& scale, int bins, Bins& scratch);
  // The split the surface-area heuristic prefers to a leaf of `count` objects: an axis (-1: none) and the
  // last bin on its left side.
  struct Split {
    int axis = -1, bin = 0;
  };
  static Split cheapestSplit(const Bins& scratch, const Vec3& scale, int bins, std::uint32_t count,
                             const Box& bounds);
  // Builds the two children of a node split at `mid`, the right one on a thread of its own where it pays;
  // returns the right child's index.
  std::uint32_t buildChildren(std::vector<BuildItem>& items, std::uint32_t begin, std::uint32_t mid,
                              std::uint32_t end, int depth, Bins& bins, std::vector<Node>& nodes,
                              int spawnLevels);
  struct Restriction;
  std::uint32_t keep(const Restriction& r, std::uint32_t wholeNode);
  void gatherKept(const Restriction& r, std::uint32_t wholeNode, Box& bounds);

  const Scene& scene_;
  const Whitted& shading_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;  // object indices, leaves point into it
};
using Bvh = BasicBvh<double>;

// A BVH over `objects` of `scene`: kept from `whole` where it is given (the restricting constructor, its
// branches of up to largestLeaf objects made leaves), built anew where it is not.
template <class Real>
BasicBvh<Real> bvhOver(const Scene& scene, const Whitted& shading, const std::vector<std::uint32_t>& objects,
                       const BvhShape* whole, std::span<const std::uint32_t> wholeIdOf,
                       std::uint32_t largestLeaf = 1) {
  if (whole == nullptr) return BasicBvh<Real>(scene, shading, objects);
  return BasicBvh<Real>(scene, shading, objects, *whole, wholeIdOf, largestLeaf);
}

// Where a float traversal may stop: a hit's t and a box's entry are each rounded within float's bits of the
// ray's reach (|origin| + t |direction|), so an object tied with the best hit so far may have its box
// entered, as computed, a few ulps beyond that hit (a unit sphere in one of radius 6e7: its hit and a
// polygon's round to one t, and the BVH passed over the sphere the reference takes). kFloatHitErrorRelative
// of the reach (2^2 ulps) beyond: such boxes are still visited, and the tie rule decides. Double's padding
// covers its rounding; its bounds are exact.
template <class Real>
struct TraversalSlack {
  explicit TraversalSlack(const BasicRay<Real>& ray) {
    if constexpr (kIsFloat<Real>) {
      Real originReach = 0, directionReach = 0;
      for (int a = 0; a < 3; ++a) {
        originReach = std::max(originReach, std::abs(ray.origin[a]));
        directionReach = std::max(directionReach, std::abs(ray.direction[a]));
      }
      const Real k = Real(kFloatHitErrorRelative);
      grow = 1 + k * directionReach;
      shrink = 1 - k * directionReach;
      offset = k * originReach;
    }
  }
  // Read at every node (tLimit falls as hits are found): one multiply-add, none in double. A traversal's
  // limit is never negative (it is at least the ray's tMin).
  Real beyond(Real t) const {
    if constexpr (kIsFloat<Real>) return t * grow + offset;
    return t;
  }
  Real before(Real t) const {
    if constexpr (kIsFloat<Real>) return t * (t >= 0 ? shrink : grow) - offset;
    return t;
  }
  Real grow = 1, shrink = 1, offset = 0;
};

template <class Real>
template <class Visit>
void BasicBvh<Real>::traverse(const BasicRay<Real>& ray, Real tFrom, const Real& tLimit,
                              TraceCounters& counters, Visit&& visit) const {
  if (nodes_.empty()) return;
  const InverseDirection<Real> inv(ray.direction);
  const TraversalSlack<Real> slack(ray);
  const Real from = slack.before(tFrom);
  struct Entry {
    std::uint32_t node;
    Real tEnter;
  };
  Entry stack[kStackSize];
  int top = 0;
  Real tEnter;
  ++counters.boxTests;
  if (!slabsHit(nodes_[0].box, ray.origin, inv, from, slack.beyond(tLimit), tEnter)) return;
  stack[top++] = Entry{0, tEnter};
  while (top > 0) {
    const Entry entry = stack[--top];
    const Real limit = slack.beyond(tLimit);
    if (entry.tEnter > limit) continue;
    const Node& node = nodes_[entry.node];
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        if (!visit(order_[i])) return;
      continue;
    }
    const std::uint32_t children[2] = {entry.node + 1, node.first};
    Real tChild[2];
    bool hit[2];
    for (int c = 0; c < 2; ++c) {
      ++counters.boxTests;
      hit[c] = slabsHit(nodes_[children[c]].box, ray.origin, inv, from, limit, tChild[c]);
    }
    // Push the farther child first so the nearer one is visited next.
    const int nearFirst = (hit[0] && hit[1] && tChild[1] < tChild[0]) ? 1 : 0;
    for (int k : {1 - nearFirst, nearFirst})
      if (hit[k]) stack[top++] = Entry{children[k], tChild[k]};
  }
}

template <class Real>
template <class Held>
double BasicBvh<Real>::transmission(const BasicRay<Real>& ray, TraceCounters& counters,
                                    std::vector<Hit>& crossed, Held&& held) const {
  crossed.clear();
  bool blocked = false;
  traverse(ray, ray.tMin, ray.tMax, counters, [&](std::uint32_t object) {
    if (!held(object)) return true;
    countTest(counters, scene_.objects[object]);
    const double t = nearestHit(scene_.objects[object], ray, ray.tMax);
    if (t == kInfinity) return true;
    if (!shading_.transmissive(object)) {
      blocked = true;
      crossed.assign(1, Hit{t, object});  // the blocker, for the caller's shadow cache
      return false;                       // an opaque object: no light, whatever else lies on the way
    }
    crossed.push_back(Hit{t, object});
    return true;
  });
  return blocked ? 0.0 : transmissionThrough(1.0, crossed, shading_);
}

}  // namespace raycube::core
