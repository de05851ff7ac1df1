#include "host/prepare/box_tree.h"

#include <algorithm>
#include <stdexcept>

namespace raycube::host {

namespace {
constexpr std::uint32_t kLeafSize = 4;

// A box as a median split sees it, kept in split order so every pass reads memory in sequence.
struct MedianItem {
  core::Box box;
  core::Vec3 centre;
};

std::vector<MedianItem> itemsOf(const std::vector<core::Box>& boxes) {
  std::vector<MedianItem> items;
  items.reserve(boxes.size());
  for (const core::Box& b : boxes) items.push_back(MedianItem{b, b.center()});
  return items;
}

// Items [begin, end): their bounds, and unless they stay a leaf, split at `mid` by the median of their
// centres along the centres' widest axis (balanced: each split halves the count).
struct MedianSplit {
  core::Box bounds;
  bool leaf = true;
  std::uint32_t mid = 0;
};
MedianSplit splitAtMedian(std::vector<MedianItem>& items, std::uint32_t begin, std::uint32_t end) {
  MedianSplit split;
  core::Box centres;
  for (std::uint32_t i = begin; i < end; ++i) {
    split.bounds.extend(items[i].box);
    centres.extend(items[i].centre);
  }
  const core::Vec3 extent = centres.extent();
  if (end - begin <= kLeafSize || !(std::max({extent.x, extent.y, extent.z}) > 0)) return split;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  split.leaf = false;
  split.mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + begin, items.begin() + split.mid, items.begin() + end,
                   [&](const MedianItem& a, const MedianItem& b) { return a.centre[axis] < b.centre[axis]; });
  return split;
}

}  // namespace

BoxTree::BoxTree(const std::vector<core::Box>& boxes, const core::BvhShape& shape) {
  if (boxes.empty()) return;
  if (shape.order.size() != boxes.size() || shape.nodes.empty())
    throw std::invalid_argument("BoxTree: the BVH's shape is not over these boxes");
  order_ = shape.order;
  leafBoxes_.reserve(order_.size());
  for (std::uint32_t o : order_) leafBoxes_.push_back(boxes[o]);
  nodes_.reserve(shape.nodes.size());
  nodes_.push_back(Node{});
  adopt(shape, 0, 0);
}

// Node `index` as the shape's node `shapeNode` (a BVH lays a subtree's objects side by side in its order, the
// left child's first), its box the bounds of its leaves' boxes.
void BoxTree::adopt(const core::BvhShape& shape, std::uint32_t shapeNode, std::uint32_t index) {
  const core::BvhShape::Node& s = shape.nodes[shapeNode];
  if (s.count > 0) {
    core::Box box;
    for (std::uint32_t i = s.first; i < s.first + s.count; ++i) box.extend(leafBoxes_[i]);
    nodes_[index] = Node{box, s.first, s.first + s.count, 0};
    return;
  }
  const std::uint32_t children = std::uint32_t(nodes_.size());
  nodes_.push_back(Node{});
  nodes_.push_back(Node{});
  adopt(shape, shapeNode + 1, children);
  adopt(shape, s.first, children + 1);
  core::Box box = nodes_[children].box;
  box.extend(nodes_[children + 1].box);
  nodes_[index] = Node{box, nodes_[children].begin, nodes_[children + 1].end, children};
}

std::vector<core::Box> medianCover(const std::vector<core::Box>& boxes, std::size_t most) {
  if (boxes.empty()) return {};
  std::vector<MedianItem> items = itemsOf(boxes);
  struct Part {
    std::uint32_t begin, end;
    MedianSplit split;
  };
  auto partOf = [&](std::uint32_t begin, std::uint32_t end) {
    return Part{begin, end, splitAtMedian(items, begin, end)};
  };
  std::vector<Part> frontier{partOf(0, std::uint32_t(items.size()))};
  const auto area = [&](std::size_t i) { return frontier[i].split.bounds.halfArea(); };
  for (;;) {
    // The largest part that splits, opened into its halves while the cover has room for one more box.
    std::size_t widest = frontier.size();
    for (std::size_t i = 0; i < frontier.size(); ++i)
      if (!frontier[i].split.leaf && (widest == frontier.size() || area(i) > area(widest))) widest = i;
    if (widest == frontier.size() || frontier.size() + 1 > most) break;
    const Part opened = frontier[widest];
    frontier[widest] = partOf(opened.begin, opened.split.mid);
    frontier.push_back(partOf(opened.split.mid, opened.end));
  }
  std::vector<core::Box> cover;
  for (const Part& p : frontier) cover.push_back(p.split.bounds);
  return cover;
}

// Found indices are distinct: a light volume reaching most of the scene (the ground polygon's) is put in
// order by marking them, in time linear in the objects; a few by sorting them.
void BoxTree::sortAscending(std::vector<std::uint32_t>& found) const {
  if (found.size() < order_.size() / 16) {
    std::sort(found.begin(), found.end());
    return;
  }
  std::vector<char> isFound(order_.size(), 0);
  for (std::uint32_t o : found) isFound[o] = 1;
  found.clear();
  for (std::uint32_t o = 0; o < isFound.size(); ++o)
    if (isFound[o]) found.push_back(o);
}

}  // namespace raycube::host
