#include "host/box_tree.h"

#include <algorithm>

namespace raycube::host {
namespace {
constexpr std::uint32_t kLeafSize = 4;
}

BoxTree::BoxTree(const std::vector<core::Box>& boxes) : order_(boxes.size()) {
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  nodes_.reserve(2 * order_.size() / kLeafSize + 2);
  if (!order_.empty()) {
    nodes_.push_back(Node{});
    build(boxes, 0, std::uint32_t(order_.size()), 0);
  }
  leafBoxes_.reserve(order_.size());
  for (std::uint32_t o : order_) leafBoxes_.push_back(boxes[o]);
}

// Fills node `index` with boxes [begin, end) of order_. Median split of the centres along the widest axis:
// balanced, so the depth is log2 of the count.
void BoxTree::build(const std::vector<core::Box>& boxes, std::uint32_t begin, std::uint32_t end,
                    std::uint32_t index) {
  core::Box bounds, centres;
  for (std::uint32_t i = begin; i < end; ++i) {
    bounds.extend(boxes[order_[i]]);
    centres.extend(boxes[order_[i]].center());
  }
  nodes_[index].box = bounds;
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  const core::Vec3 extent = centres.extent();
  if (end - begin <= kLeafSize || !(std::max({extent.x, extent.y, extent.z}) > 0)) return;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) { return boxes[a].center()[axis] < boxes[b].center()[axis]; });
  // Children next to each other, their subtrees after them.
  const std::uint32_t children = std::uint32_t(nodes_.size());
  nodes_.push_back(Node{});
  nodes_.push_back(Node{});
  nodes_[index].children = children;
  build(boxes, begin, mid, children);
  build(boxes, mid, end, children + 1);
}

// Found indices are distinct: a light volume reaching most of the scene (the ground polygon's) is put in order
// by marking them, in time linear in the objects; a few by sorting them.
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
