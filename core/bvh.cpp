#include "core/bvh.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <thread>

#include "core/precision.h"
#include "core/transmission.h"

namespace raycube::core {

namespace {
constexpr std::uint32_t kLeafSize = 1;
// A build on every core spawns a thread for the right subtree of the first two splits whose smaller side
// holds at least kSpawnObjects / 2 objects (four subtrees: an uneven split still leaves two cores busy; a
// thread costs tens of microseconds, two thousand objects' build about a millisecond).
constexpr int kSpawnLevels = 2;
constexpr std::uint32_t kSpawnObjects = 4096;
}  // namespace

std::vector<std::uint32_t> everyObjectOf(const Scene& scene) {
  std::vector<std::uint32_t> all(scene.objects.size());
  for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  return all;
}

template <class Real>
BasicBvh<Real>::BasicBvh(const Scene& scene, const Whitted& shading, BuildOn on)
    : BasicBvh(scene, shading, everyObjectOf(scene), on) {}

template <class Real>
BasicBvh<Real>::BasicBvh(const Scene& scene, const Whitted& shading, std::vector<std::uint32_t> objects,
                         BuildOn on)
    : scene_(scene), shading_(shading), order_(std::move(objects)) {
  std::vector<BuildItem> items;
  items.reserve(order_.size());
  for (std::uint32_t o : order_) {
    const Box box = boundsOf(scene.objects[o], kBoxPaddingRelativeOf<Real>);
    items.push_back(BuildItem{box, box.center(), o});
  }
  nodes_.reserve(2 * order_.size() + 1);
  Bins bins;
  if (!items.empty())
    build(items, 0, std::uint32_t(items.size()), 0, bins, nodes_,
          on == BuildOn::EveryCore ? kSpawnLevels : 0);
  for (std::size_t i = 0; i < items.size(); ++i) order_[i] = items[i].object;
}

template <class Real>
BvhShape BasicBvh<Real>::shape() const {
  BvhShape out;
  out.order = order_;
  out.nodes.reserve(nodes_.size());
  for (const Node& n : nodes_) out.nodes.push_back(BvhShape::Node{n.first, n.count, n.axis});
  out.parent.assign(nodes_.size(), 0);
  out.leafOf.assign(scene_.objects.size(), 0);
  for (std::uint32_t n = 0; n < nodes_.size(); ++n) {
    if (nodes_[n].count > 0) {
      for (std::uint32_t i = nodes_[n].first; i < nodes_[n].first + nodes_[n].count; ++i)
        out.leafOf[order_[i]] = n;
    } else {
      out.parent[n + 1] = n;
      out.parent[nodes_[n].first] = n;
    }
  }
  return out;
}

// What the restricting constructor keeps of the whole tree: how many of its objects each whole node holds
// (the nodes above its objects' leaves hold some), and which object of this scene each whole-scene object of
// those leaves is (kNotHeld if none): one lookup per object in a table as long as the whole scene, where
// sorting the objects by whole id and searching them cost most of the restriction (BM_BvhRestrict).
template <class Real>
struct BasicBvh<Real>::Restriction {
  static constexpr std::uint32_t kNotHeld = std::numeric_limits<std::uint32_t>::max();
  static constexpr std::uint8_t kLargestSaturation = 255;
  const BvhShape& whole;
  // Per whole node, saturating at saturated = largestLeaf + 1: all the restriction asks of a count is
  // whether it is 0 or at most largestLeaf, and an object's walk up from its leaf stops at the first node
  // already saturated, every node above it being saturated too (BM_BvhRestrict times it).
  std::vector<std::uint8_t> keptBelow;
  std::vector<std::uint32_t> localOf;  // per whole object
  std::uint32_t largestLeaf;
  std::uint8_t saturated;
};

template <class Real>
BasicBvh<Real>::BasicBvh(const Scene& scene, const Whitted& shading,
                         const std::vector<std::uint32_t>& objects, const BvhShape& whole,
                         std::span<const std::uint32_t> wholeIdOf, std::uint32_t largestLeaf)
    : scene_(scene), shading_(shading) {
  if (objects.empty()) return;
  if (largestLeaf == 0 || largestLeaf >= Restriction::kLargestSaturation)
    throw std::invalid_argument("a restricted BVH's leaves hold 1 to 254 objects");
  // A byte per whole node, as much temporary memory as a flag: 64 processors restrict at once.
  Restriction r{whole, std::vector<std::uint8_t>(whole.nodes.size(), 0),
                std::vector<std::uint32_t>(whole.leafOf.size(), Restriction::kNotHeld), largestLeaf,
                std::uint8_t(largestLeaf + 1)};
  std::size_t marked = 0;
  for (std::uint32_t o : objects) {
    const std::uint32_t id = wholeIdOf.empty() ? o : wholeIdOf[o];
    r.localOf[id] = o;
    // Count the object on the way up from its leaf, as far as a count already saturated.
    for (std::uint32_t n = whole.leafOf[id]; r.keptBelow[n] < r.saturated; n = whole.parent[n]) {
      marked += r.keptBelow[n]++ == 0;
      if (n == 0) break;
    }
  }
  // The copy has at most the marked nodes: reserved, not doubled as it grows (a doubled vector's unused
  // capacity is a large share of 64 processors' trees). Not shrunk to fit: the capacity
  // past the last node is never written, so costs no memory, where a copy would leave the tree's pages
  // twice in the processor's allocator, raising the peak.
  nodes_.reserve(marked);
  order_.reserve(objects.size());
  keep(r, 0);
}

// Copies the kept part of the whole tree's node (keptBelow[wholeNode] > 0), depth first as build lays nodes
// out; an inner node with one kept child becomes that child, and one holding at most r.largestLeaf kept
// objects becomes a leaf of them. Returns the copy's index.
template <class Real>
std::uint32_t BasicBvh<Real>::keep(const Restriction& r, std::uint32_t wholeNode) {
  const BvhShape::Node& w = r.whole.nodes[wholeNode];
  const bool inner = w.count == 0;
  if (inner) {
    const std::uint32_t left = wholeNode + 1, right = w.first;
    if (r.keptBelow[left] == 0) return keep(r, right);
    if (r.keptBelow[right] == 0) return keep(r, left);
  }
  const std::uint32_t index = std::uint32_t(nodes_.size());
  nodes_.push_back(Node{});
  if (!inner || r.keptBelow[wholeNode] <= r.largestLeaf) {
    Box bounds;
    const std::uint32_t first = std::uint32_t(order_.size());
    gatherKept(r, wholeNode, bounds);
    nodes_[index] = Node{bounds.template enclosingIn<Real>(), first, std::uint32_t(order_.size()) - first, 0};
    return index;
  }
  keep(r, wholeNode + 1);
  const std::uint32_t right = keep(r, w.first);
  BasicBox<Real> box = nodes_[index + 1].box;
  box.extend(nodes_[right].box);
  nodes_[index] = Node{box, right, 0, w.axis};
  return index;
}

// Appends the kept objects below the whole tree's node to order_, in the whole tree's order, with their
// boxes into `bounds`.
template <class Real>
void BasicBvh<Real>::gatherKept(const Restriction& r, std::uint32_t wholeNode, Box& bounds) {
  if (r.keptBelow[wholeNode] == 0) return;
  const BvhShape::Node& w = r.whole.nodes[wholeNode];
  if (w.count == 0) {
    gatherKept(r, wholeNode + 1, bounds);
    gatherKept(r, w.first, bounds);
    return;
  }
  for (std::uint32_t i = w.first; i < w.first + w.count; ++i)
    if (const std::uint32_t local = r.localOf[r.whole.order[i]]; local != Restriction::kNotHeld) {
      order_.push_back(local);
      bounds.extend(boundsOf(scene_.objects[local], kBoxPaddingRelativeOf<Real>));
    }
}

namespace {

constexpr double kTraversalCost = 1.0;  // relative to one ray-object test

// Bins per unit of centroid extent along each axis; 0 where the centroids do not spread.
Vec3 binScale(const Box& centroids, int bins) {
  Vec3 scale;
  for (int axis = 0; axis < 3; ++axis) {
    const double width = centroids.hi[axis] - centroids.lo[axis];
    scale[axis] = width > 0 ? bins / width : 0.0;
  }
  return scale;
}

// The bin of a centroid, always one of the node's: a centre that is not a number (an object box infinite
// both ways, from a hither of 1e300) or beyond the last bin's edge is binned at an end, never indexed
// outside the bins (int(NaN) is undefined; it was a segfault).
int binOf(double centre, double lo, double scale, int bins) {
  const double at = (centre - lo) * scale;
  return at >= 0 ? int(std::min(double(bins - 1), at)) : 0;
}

}  // namespace

// Binned surface-area heuristic over object centroids (Wald 2007); a leaf when no split pays.
template <class Real>
std::uint32_t BasicBvh<Real>::build(std::vector<BuildItem>& items, std::uint32_t begin, std::uint32_t end,
                                    int depth, Bins& scratch, std::vector<Node>& nodes, int spawnLevels) {
  const std::uint32_t index = std::uint32_t(nodes.size());
  nodes.push_back(Node{});
  Box bounds, centroids;
  for (std::uint32_t i = begin; i < end; ++i) {
    bounds.extend(items[i].box);
    centroids.extend(items[i].centre);
  }
  nodes[index].box = bounds.template enclosingIn<Real>();
  const std::uint32_t count = end - begin;
  // A bin per object in small nodes (no cost to set up bins nothing falls in), kBins in large ones.
  const int bins = int(std::min<std::uint32_t>(count, kBins));
  const bool split = count > kLeafSize && depth < kMaxDepth;
  const Vec3 scale = binScale(centroids, bins);
  Split best;
  if (split) {
    fillBins(items, begin, end, centroids, scale, bins, scratch);
    best = cheapestSplit(scratch, scale, bins, count, bounds);
  }
  const int bestAxis = best.axis, bestBin = best.bin;
  if (bestAxis < 0) {
    nodes[index].first = begin;
    nodes[index].count = count;
    return index;
  }
  const double lo = centroids.lo[bestAxis], axisScale = scale[bestAxis];
  const auto midIt = std::partition(items.begin() + begin, items.begin() + end, [&](const BuildItem& item) {
    return binOf(item.centre[bestAxis], lo, axisScale, bins) <= bestBin;
  });
  const std::uint32_t mid = std::uint32_t(midIt - items.begin());
  const std::uint32_t right = buildChildren(items, begin, mid, end, depth, scratch, nodes, spawnLevels);
  nodes[index].first = right;
  nodes[index].axis = std::uint8_t(bestAxis);
  return index;
}

template <class Real>
void BasicBvh<Real>::fillBins(const std::vector<BuildItem>& items, std::uint32_t begin, std::uint32_t end,
                              const Box& centroids, const Vec3& scale, int bins, Bins& scratch) {
  auto& binBoxes = scratch.boxes;
  auto& binCounts = scratch.counts;
  for (int axis = 0; axis < 3; ++axis) {
    std::fill_n(binBoxes[axis], bins, Box{});
    std::fill_n(binCounts[axis], kBins, 0u);  // all of them: a fixed length fills in two stores
  }
  for (std::uint32_t i = begin; i < end; ++i) {
    const Box& box = items[i].box;
    const Vec3& centre = items[i].centre;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(scale[axis] > 0)) continue;
      const int b = binOf(centre[axis], centroids.lo[axis], scale[axis], bins);
      binBoxes[axis][b].extend(box);
      ++binCounts[axis][b];
    }
  }
}

template <class Real>
typename BasicBvh<Real>::Split BasicBvh<Real>::cheapestSplit(const Bins& scratch, const Vec3& scale, int bins,
                                                             std::uint32_t count, const Box& bounds) {
  Split best;
  double bestCost = double(count);                                // cost of a leaf, in object tests
  double bestWeighted = std::numeric_limits<double>::infinity();  // the best split's areas times counts
  for (int axis = 0; axis < 3; ++axis) {
    if (!(scale[axis] > 0)) continue;
    const Box* binBox = scratch.boxes[axis];
    const std::uint32_t* binCount = scratch.counts[axis];
    double rightArea[kBins];
    std::uint32_t rightCount[kBins];
    Box acc;
    std::uint32_t n = 0;
    for (int b = bins - 1; b > 0; --b) {
      acc.extend(binBox[b]);
      n += binCount[b];
      rightArea[b] = acc.halfArea();
      rightCount[b] = n;
    }
    acc = Box{};
    n = 0;
    for (int b = 0; b < bins - 1; ++b) {
      acc.extend(binBox[b]);
      n += binCount[b];
      if (n == 0 || rightCount[b + 1] == 0) continue;
      // Rounding is monotonic: a candidate whose area-weighted count is no smaller than the best one's
      // cannot cost less, and needs no division.
      const double weighted = acc.halfArea() * n + rightArea[b + 1] * rightCount[b + 1];
      if (!(weighted < bestWeighted)) continue;
      const double cost = kTraversalCost + weighted / bounds.halfArea();
      if (cost < bestCost) {
        bestCost = cost;
        bestWeighted = weighted;
        best.axis = axis;
        best.bin = b;
      }
    }
  }
  return best;
}

template <class Real>
std::uint32_t BasicBvh<Real>::buildChildren(std::vector<BuildItem>& items, std::uint32_t begin,
                                            std::uint32_t mid, std::uint32_t end, int depth, Bins& scratch,
                                            std::vector<Node>& nodes, int spawnLevels) {
  std::uint32_t right;
  // Only a split into two large parts is worth a thread; past a lopsided one (a large sphere beside the
  // rest), the larger part may still split evenly further down.
  const bool spawn = spawnLevels > 0 && std::min(mid - begin, end - mid) >= kSpawnObjects / 2;
  if (spawn) {
    // The two subtrees' items are disjoint ranges of `items`, their nodes separate vectors until joined.
    std::vector<Node> rightNodes;
    std::thread rightBuilder([&, mid, end] {
      Bins bins;
      rightNodes.reserve(2 * std::size_t(end - mid));
      build(items, mid, end, depth + 1, bins, rightNodes, spawnLevels - 1);
    });
    build(items, begin, mid, depth + 1, scratch, nodes, spawnLevels - 1);
    rightBuilder.join();
    right = std::uint32_t(nodes.size());
    for (Node n : rightNodes) {
      if (n.count == 0) n.first += right;  // an inner node's right child, now further on
      nodes.push_back(n);
    }
  } else {
    build(items, begin, mid, depth + 1, scratch, nodes, spawnLevels);
    right = build(items, mid, end, depth + 1, scratch, nodes, spawnLevels);
  }
  return right;
}

// The best t so far, in Real, limits the traversal; a float t converts to the Hit's double exactly.
template <class Real>
Hit BasicBvh<Real>::closestHit(const BasicRay<Real>& ray, TraceCounters& counters) const {
  Hit best;
  Real bestT = std::numeric_limits<Real>::infinity();
  traverse(ray, ray.tMin, bestT, counters, [&](std::uint32_t object) {
    countTest(counters, scene_.objects[object]);
    const Hit h{nearestHit(scene_.objects[object], ray, std::numeric_limits<Real>::infinity()), object};
    if (h.t < kInfinity && h.closerThan(best)) {
      best = h;
      bestT = roundedTowards<Real>(h.t, kInfinity);
    }
    return true;
  });
  return best;
}

template <class Real>
double BasicBvh<Real>::transmission(const BasicRay<Real>& ray, TraceCounters& counters,
                                    std::vector<Hit>& crossed) const {
  return transmission(ray, counters, crossed, [](std::uint32_t) { return true; });
}

template class BasicBvh<float>;
template class BasicBvh<double>;

}  // namespace raycube::core
