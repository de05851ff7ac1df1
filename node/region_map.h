#pragma once
// Which processor owns which pixel area (Priol & Bouatouch 3.1): an R x C grid of sample rectangles with
// nearly equal sample counts, processors numbered row by row. A node uses it to name the owner of a point
// and the neighbour behind a face; it knows nothing of how the host chose the areas.
#include <algorithm>
#include <vector>

#include "node/eye_frame_ray.h"
#include "node/ray_message.h"
#include "node/screen_grid.h"

namespace raycube::node {

class RegionMap {
 public:
  RegionMap(std::vector<int> columnStarts, std::vector<int> rowStarts, const ScreenLines& lines)
      : columnStarts_(std::move(columnStarts)), rowStarts_(std::move(rowStarts)) {
    for (int k : columnStarts_) sBounds_.push_back(lines.at(0, k));
    for (int k : rowStarts_) qBounds_.push_back(lines.at(1, k));
  }

  int columns() const { return int(columnStarts_.size()) - 1; }
  int rows() const { return int(rowStarts_.size()) - 1; }
  int processors() const { return columns() * rows(); }
  int idOf(int row, int column) const { return row * columns() + column; }
  int rowOf(int id) const { return id / columns(); }
  int columnOf(int id) const { return id % columns(); }
  SampleRect areaOf(int id) const {
    return SampleRect{columnStarts_[columnOf(id)], columnStarts_[columnOf(id) + 1], rowStarts_[rowOf(id)],
                      rowStarts_[rowOf(id) + 1]};
  }

  // The processor whose region holds the ray at t (front part only).
  int ownerAt(const EyeFrameRay& ray, double t) const {
    return idOf(locate(qBounds_, ray.screenAt(1, t)), locate(sBounds_, ray.screenAt(0, t)));
  }
  int ownerOfSample(int sx, int sy) const {
    const auto col = std::upper_bound(columnStarts_.begin() + 1, columnStarts_.end() - 1, sx) - columnStarts_.begin() - 1;
    const auto row = std::upper_bound(rowStarts_.begin() + 1, rowStarts_.end() - 1, sy) - rowStarts_.begin() - 1;
    return idOf(int(row), int(col));
  }

  // Dimension-order routing on the 2D array: along the row first, then along the column.
  Face nextHop(int from, int to) const {
    if (columnOf(to) < columnOf(from)) return Face::Left;
    if (columnOf(to) > columnOf(from)) return Face::Right;
    return rowOf(to) < rowOf(from) ? Face::Up : Face::Down;
  }
  int neighbour(int id, Face face) const {
    const int r = rowOf(id), c = columnOf(id);
    switch (face) {
      case Face::Left: return c > 0 ? idOf(r, c - 1) : -1;
      case Face::Right: return c + 1 < columns() ? idOf(r, c + 1) : -1;
      case Face::Up: return r > 0 ? idOf(r - 1, c) : -1;
      case Face::Down: return r + 1 < rows() ? idOf(r + 1, c) : -1;
    }
    return -1;
  }

 private:
  static int locate(const std::vector<double>& bounds, double value) {
    return int(std::upper_bound(bounds.begin() + 1, bounds.end() - 1, value) - (bounds.begin() + 1));
  }

  std::vector<int> columnStarts_, rowStarts_;
  std::vector<double> sBounds_, qBounds_;
};

}  // namespace raycube::node
