#include "node/region_cells.h"

#include <algorithm>
#include <stdexcept>

namespace raycube::node {
namespace {

// Recursive halving of [lo, hi) `level` times, as sample-index boundaries (duplicates removed).
std::vector<int> halvings(int lo, int hi, int level) {
  std::vector<int> cuts{lo, hi};
  for (int l = 0; l < level; ++l) {
    std::vector<int> next;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      next.push_back(cuts[k]);
      if (cuts[k + 1] - cuts[k] >= 2) next.push_back((cuts[k] + cuts[k + 1]) / 2);
    }
    next.push_back(hi);
    cuts = next;
  }
  return cuts;
}

}  // namespace

RegionCells::RegionCells(const SampleRect& area, const ScreenLines& lines, int level, bool depthCuts,
                         const std::vector<std::uint32_t>& objects, const std::vector<EyeBox>& boxes,
                         bool unbounded) {
  if (boxes.size() != objects.size())
    throw std::invalid_argument("a region's cells need one eye box per object of the region");
  sampleBounds_[0] = halvings(area.x0, area.x1, level);
  sampleBounds_[1] = halvings(area.y0, area.y1, level);
  for (int axis = 0; axis < 2; ++axis) {
    for (int k : sampleBounds_[axis]) bounds_[axis].push_back(lines.at(axis, k));
    if (unbounded) {
      bounds_[axis].front() = -core::kInfinity;
      bounds_[axis].back() = core::kInfinity;
    }
  }
  columnsX_ = int(bounds_[0].size()) - 1;
  const int rows = int(bounds_[1].size()) - 1;
  std::vector<char> held(objects.size(), 0);  // per entry of `objects`
  columns_.resize(std::size_t(columnsX_) * rows);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columnsX_; ++i) {
      ColumnSlab slab{bounds_[0][i], bounds_[0][i + 1], bounds_[1][j], bounds_[1][j + 1], 0, core::kInfinity};
      std::vector<std::size_t> inColumn;  // entries of `objects`
      std::vector<double> splits;
      for (std::size_t k = 0; k < objects.size(); ++k) {
        const EyeBox& box = boxes[k];
        if (!mayTouch(box, slab)) continue;
        inColumn.push_back(k);
        if (depthCuts && box.lo.z > 0) splits.push_back(box.lo.z);
        if (depthCuts && box.hi.z > 0) splits.push_back(box.hi.z);
      }
      std::sort(splits.begin(), splits.end());
      splits.erase(std::unique(splits.begin(), splits.end()), splits.end());
      Column& column = columns_[std::size_t(j) * columnsX_ + i];
      column.depthSplits = splits;
      column.cellObjects.resize(splits.size() + 1);
      for (std::size_t cut = 0; cut <= splits.size(); ++cut) {
        slab.zLo = cut == 0 ? 0.0 : splits[cut - 1];
        slab.zHi = cut == splits.size() ? core::kInfinity : splits[cut];
        for (std::size_t k : inColumn)
          if (mayTouch(boxes[k], slab)) {
            column.cellObjects[cut].push_back(objects[k]);
            held[k] = 1;
          }
      }
      cellCount_ += column.cellObjects.size();
    }
  }
  objectCount_ = std::size_t(std::count(held.begin(), held.end(), 1));
  oneCell_ = columns_.size() == 1 && columns_.front().depthSplits.empty();
}

int RegionCells::locateIn(const std::vector<double>& bounds, double value) {
  // Interior boundaries only: values beyond the outer ones (or NaN) clamp to the first/last interval.
  const auto first = bounds.begin() + 1, last = bounds.end() - 1;
  return int(std::upper_bound(first, last, value) - first);
}

void RegionCells::locate(const EyeFrameRay& ray, double t, int& column, int& row) const {
  // A single super-cell across an axis (a BVH region's one column) needs no lookup: locateIn's 0.
  column = columnsX_ == 1 ? 0 : locateIn(bounds_[0], ray.screenAt(0, t));
  row = bounds_[1].size() == 2 ? 0 : locateIn(bounds_[1], ray.screenAt(1, t));
}

void RegionCells::locateSample(int sx, int sy, int& column, int& row) const {
  column = int(std::upper_bound(sampleBounds_[0].begin() + 1, sampleBounds_[0].end() - 1, sx) -
               (sampleBounds_[0].begin() + 1));
  row = int(std::upper_bound(sampleBounds_[1].begin() + 1, sampleBounds_[1].end() - 1, sy) -
            (sampleBounds_[1].begin() + 1));
}

}  // namespace raycube::node
