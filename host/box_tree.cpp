#include "host/box_tree.h"

#include <algorithm>

namespace raycube::host {
namespace {
constexpr std::uint32_t kLeafSize = 4;
}

BoxTree::BoxTree(const std::vector<core::Box>& boxes) {
  std::vector<Item> items;
  items.reserve(boxes.size());
  for (std::uint32_t i = 0; i < boxes.size(); ++i) items.push_back(Item{boxes[i], boxes[i].center(), i});
  nodes_.reserve(2 * items.size() / kLeafSize + 2);
  if (!items.empty()) {
    nodes_.push_back(Node{});
    build(items, 0, std::uint32_t(items.size()), 0);
  }
  order_.reserve(items.size());
  leafBoxes_.reserve(items.size());
  for (const Item& item : items) {
    order_.push_back(item.object);
    leafBoxes_.push_back(item.box);
  }
}

// Fills node `index` with items [begin, end). Median split of the centres along the widest axis: balanced,
// so the depth is log2 of the count.
void BoxTree::build(std::vector<Item>& items, std::uint32_t begin, std::uint32_t end, std::uint32_t index) {
  core::Box bounds, centres;
  for (std::uint32_t i = begin; i < end; ++i) {
    bounds.extend(items[i].box);
    centres.extend(items[i].centre);
  }
  nodes_[index].box = bounds;
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  const core::Vec3 extent = centres.extent();
  if (end - begin <= kLeafSize || !(std::max({extent.x, extent.y, extent.z}) > 0)) return;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                   [&](const Item& a, const Item& b) { return a.centre[axis] < b.centre[axis]; });
  // Children next to each other, their subtrees after them.
  const std::uint32_t children = std::uint32_t(nodes_.size());
  nodes_.push_back(Node{});
  nodes_.push_back(Node{});
  nodes_[index].children = children;
  build(items, begin, mid, children);
  build(items, mid, end, children + 1);
}

std::vector<core::Box> BoxTree::cover(std::size_t most) const {
  if (nodes_.empty()) return {};
  const auto area = [&](std::uint32_t n) { return nodes_[n].box.halfArea(); };
  std::vector<std::uint32_t> frontier{0};
  for (;;) {
    // The largest node with children, opened into them while the cover has room for one more box.
    std::size_t widest = frontier.size();
    for (std::size_t i = 0; i < frontier.size(); ++i)
      if (nodes_[frontier[i]].children != 0 && (widest == frontier.size() || area(frontier[i]) > area(frontier[widest])))
        widest = i;
    if (widest == frontier.size() || frontier.size() + 1 > most) break;
    const std::uint32_t children = nodes_[frontier[widest]].children;
    frontier[widest] = children;
    frontier.push_back(children + 1);
  }
  std::vector<core::Box> boxes;
  for (std::uint32_t n : frontier) boxes.push_back(nodes_[n].box);
  return boxes;
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
