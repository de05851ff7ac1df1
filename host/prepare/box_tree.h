#pragma once
// The host's spatial index for pruning (3.2 step 1, 3.7.2): a binary tree of boxes over the objects, so that
// finding the objects a region or a light volume may hold costs about (objects found) x log(objects), not a
// test of every object. The test must be monotone (a box that fails it holds no box that passes it), as
// every test of node/eye_box.h and host/prepare/light_volume.h is: a subtree whose box fails is skipped
// whole. What a query finds does not depend on the tree's shape, only how fast it finds it.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/box.h"
#include "core/bvh.h"

namespace raycube::host {

class BoxTree {
 public:
  // The shape of a BVH over the same objects (its order lists every index of `boxes`), with these boxes'
  // own bounds: linear in the objects where a build of its own would be n log n (the host's sampling BVH is
  // at hand).
  BoxTree(const std::vector<core::Box>& boxes, const core::BvhShape& shape);

  // Indices of the boxes passing mayHold(box), whose every enclosing node also passes, in ascending order.
  // holdsAll(box), when it can tell, says that every box inside `box` passes: the subtree is taken whole.
  template <class MayHold, class HoldsAll>
  std::vector<std::uint32_t> query(MayHold&& mayHold, HoldsAll&& holdsAll) const;
  template <class MayHold>
  std::vector<std::uint32_t> query(MayHold&& mayHold) const {
    return query(mayHold, [](const core::Box&) { return false; });
  }

 private:
  struct Node {
    core::Box box;
    std::uint32_t begin = 0, end = 0;  // the range of order_ its subtree holds
    std::uint32_t children = 0;        // inner: left child here, right child next; 0: a leaf
  };
  void adopt(const core::BvhShape& shape, std::uint32_t shapeNode, std::uint32_t index);
  void sortAscending(std::vector<std::uint32_t>& found) const;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> order_;  // object indices, leaves point into it
  std::vector<core::Box> leafBoxes_;  // per entry of order_
};

// At most `most` boxes (at least one, unless there are none) that together hold every box: the parts of
// median splits of the boxes' centres along their widest axis, opening the largest part first, so the cover
// hugs the boxes as closely as that many boxes can. Only the parts opened are split.
std::vector<core::Box> medianCover(const std::vector<core::Box>& boxes, std::size_t most);

template <class MayHold, class HoldsAll>
std::vector<std::uint32_t> BoxTree::query(MayHold&& mayHold, HoldsAll&& holdsAll) const {
  std::vector<std::uint32_t> found;
  if (nodes_.empty()) return found;
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (!mayHold(node.box)) continue;
    if (holdsAll(node.box)) {
      found.insert(found.end(), order_.begin() + node.begin, order_.begin() + node.end);
    } else if (node.children != 0) {
      stack.push_back(node.children);
      stack.push_back(node.children + 1);
    } else {
      for (std::uint32_t i = node.begin; i < node.end; ++i)
        if (mayHold(leafBoxes_[i])) found.push_back(order_[i]);
    }
  }
  sortAscending(found);
  return found;
}

}  // namespace raycube::host
