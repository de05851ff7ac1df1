#pragma once
// Priol & Bouatouch 3.3: a node subdivides its pyramidal region into cells. Its pixel area is halved
// recursively in x and y to a settable level (super-cells, columns of screen space), and each column is cut
// by the depth faces of its objects' bounding boxes (depth partitioning). A ray walks from cell to cell in
// t order; each cell owns the half-open interval [t_enter, t_exit) of the ray inside it.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "node/eye_box.h"
#include "node/eye_frame_ray.h"
#include "node/screen_grid.h"

namespace raycube::node {

// Where a walk left the region: the faces crossed (-1, 0, +1 along s and q) at t.
struct RegionExit {
  double t = 0;
  int sStep = 0;
  int qStep = 0;
};

enum class WalkResult : std::uint8_t { Stopped, Finished, Exited };

// How a region organises its objects. Paper: the cells of 3.3. Bvh: one cell spanning the whole region (its
// pyramid still bounds the ray's interval), whose objects a BVH visits: the paper's cells suit a few
// objects, their depth cuts explode on thousands, a BVH's cost grows about logarithmically. Auto: a BVH in
// every region on real cores; the host gives the emulated machine the paper's cells
// (host/machine/machine_settings.h).
enum class CellStructure : std::uint8_t { Auto, Paper, Bvh };

// Auto on real cores. Until a region of one cell walked in one pass (RegionCells::walkOneCell), the paper's
// cells served regions of at most 8 objects; since, a BVH region costs fewer instructions there too, down
// to the empty regions the paper's cells crossed column by column (counted under callgrind, and timed).
inline CellStructure chosenFor(CellStructure requested) {
  return requested == CellStructure::Auto ? CellStructure::Bvh : requested;
}

// Where the ray meets the face ahead of it of the slab [lo, hi) of screen coordinate `axis` (a super-cell
// column or row, a region): dir is the sign of that coordinate's change along the ray; infinity where it
// moves along neither way.
inline double faceAhead(const EyeFrameRay& ray, int axis, int dir, double lo, double hi) {
  return dir > 0 ? ray.planeCrossing(axis, hi) : dir < 0 ? ray.planeCrossing(axis, lo) : core::kInfinity;
}

class RegionCells {
 public:
  // objects: indices into the database, and the eye box of each (boxes[k] is objects[k]'s); only those
  // touching the region are kept.
  // depthCuts: cut each column by its objects' depth faces (3.3); without, a column is one cell.
  // unbounded: the outermost faces pushed to infinity, as the screen's edge regions' are (3.1): the cells
  // cover everything in front of the eye (a light volume's objects, 3.7.2), the outer columns widest.
  RegionCells(const SampleRect& area, const ScreenLines& lines, int level, bool depthCuts,
              const std::vector<std::uint32_t>& objects, const std::vector<EyeBox>& boxes,
              bool unbounded = false);

  // Walks [t, tEnd) from the column containing the ray at t (or the given sample's column for eye rays),
  // calling visit(tEnter, tExit, objectIndices) for every non-empty cell interval, in t order, until visit
  // returns false (Stopped), tEnd is reached (Finished), or the ray leaves the region (Exited, with exit).
  template <class Visit>
  WalkResult walk(const EyeFrameRay& ray, double t, double tEnd, int column, int row, Visit&& visit,
                  RegionExit& exit, std::uint64_t& cellSteps) const {
    return oneCell_ ? walkOneCell(ray, t, tEnd, visit, exit, cellSteps)
                    : walkColumns(ray, t, tEnd, column, row, visit, exit, cellSteps);
  }
  // The walk through columns and their cells, whatever the region; walk() takes it but for a region of one
  // cell (a BVH region's), whose single pass it makes with the same arithmetic.
  template <class Visit>
  WalkResult walkColumns(const EyeFrameRay& ray, double t, double tEnd, int column, int row, Visit&& visit,
                         RegionExit& exit, std::uint64_t& cellSteps) const;

  // Super-cell column and row containing the ray at t (clamped into the region: 3.3.1, entry cell).
  void locate(const EyeFrameRay& ray, double t, int& column, int& row) const;
  void locateSample(int sx, int sy, int& column, int& row) const;

  std::size_t cellCount() const { return cellCount_; }
  std::size_t objectCount() const { return objectCount_; }  // distinct objects in the region's cells

 private:
  struct Column {
    std::vector<double> depthSplits;                      // ascending; cell k is [split k-1, split k)
    std::vector<std::vector<std::uint32_t>> cellObjects;  // depthSplits.size() + 1 cells
  };
  const Column& column(int i, int j) const { return columns_[std::size_t(j) * columnsX_ + i]; }
  static int locateIn(const std::vector<double>& bounds, double value);
  template <class Visit>
  WalkResult walkOneCell(const EyeFrameRay& ray, double t, double tEnd, Visit&& visit, RegionExit& exit,
                         std::uint64_t& cellSteps) const;

  // bounds_[axis]: screen coordinates of the super-cell boundaries (first/last may be infinite)
  std::vector<double> bounds_[2];
  std::vector<int> sampleBounds_[2];
  std::vector<Column> columns_;
  int columnsX_ = 0;
  bool oneCell_ = false;  // one super-cell, no depth cut: the region is a single cell
  std::size_t cellCount_ = 0;
  std::size_t objectCount_ = 0;
};

// A ray's way through a cell spanning the screen's rectangle `cell` (a region of one cell), from t to at
// most tEnd: the cell's interval [t, end), and whether the ray reaches tEnd in it or leaves it through the
// faces of `exit` (a crossing rounded behind t leaves at once; no face at all where a NaN hid it).
struct CellPassage {
  double end = 0;
  bool reachesEnd = false;
  RegionExit exit;
};
inline CellPassage passageThrough(const EyeFrameRay& ray, double t, double tEnd, const ScreenRect& cell) {
  const int sDir = ray.screenDirection(0), qDir = ray.screenDirection(1);
  const double tS = faceAhead(ray, 0, sDir, cell.s0, cell.s1), tQ = faceAhead(ray, 1, qDir, cell.q0, cell.q1);
  CellPassage p;
  p.end = std::max(t, std::min({tS, tQ, tEnd}));
  p.reachesEnd = tEnd <= tS && tEnd <= tQ;
  p.exit = RegionExit{p.end, tS <= p.end && sDir != 0 ? sDir : 0, tQ <= p.end && qDir != 0 ? qDir : 0};
  return p;
}

// walkColumns' first pass through a region of one cell: the column's faces ahead, the cell's interval, and
// out through the faces crossed where it ends.
template <class Visit>
WalkResult RegionCells::walkOneCell(const EyeFrameRay& ray, double t, double tEnd, Visit&& visit,
                                    RegionExit& exit, std::uint64_t& cellSteps) const {
  const CellPassage p =
      passageThrough(ray, t, tEnd, ScreenRect{bounds_[0][0], bounds_[0][1], bounds_[1][0], bounds_[1][1]});
  ++cellSteps;
  const std::vector<std::uint32_t>& objects = columns_.front().cellObjects.front();
  if (p.end > t && !objects.empty() && !visit(t, p.end, objects)) return WalkResult::Stopped;
  if (p.reachesEnd) return WalkResult::Finished;
  if (p.exit.sStep == 0 && p.exit.qStep == 0)  // no face crossed (a NaN): on as walkColumns would go on
    return walkColumns(ray, p.end, tEnd, 0, 0, visit, exit, cellSteps);
  exit = p.exit;
  return WalkResult::Exited;
}

template <class Visit>
WalkResult RegionCells::walkColumns(const EyeFrameRay& ray, double t, double tEnd, int i, int j,
                                    Visit&& visit, RegionExit& exit, std::uint64_t& cellSteps) const {
  const int sDir = ray.screenDirection(0), qDir = ray.screenDirection(1);
  const int zDir = (ray.d.z > 0) - (ray.d.z < 0);
  for (;;) {
    // The column's exit: the face ahead along s, along q, or the end of the interval. A crossing computed
    // behind t (rounding) leaves the column at once with an empty interval.
    const double tS = faceAhead(ray, 0, sDir, bounds_[0][i], bounds_[0][i + 1]);
    const double tQ = faceAhead(ray, 1, qDir, bounds_[1][j], bounds_[1][j + 1]);
    const double tColumn = std::max(t, std::min({tS, tQ, tEnd}));
    const Column& col = column(i, j);
    // Depth partitioning: walk the column's cells in z order.
    const std::vector<double>& splits = col.depthSplits;
    int k =
        splits.empty() ? 0 : int(std::upper_bound(splits.begin(), splits.end(), ray.zAt(t)) - splits.begin());
    for (;;) {
      double tCell = tColumn;
      if (zDir > 0 && k < int(splits.size())) tCell = std::min(tCell, ray.depthCrossing(splits[k]));
      if (zDir < 0 && k > 0) tCell = std::min(tCell, ray.depthCrossing(splits[k - 1]));
      tCell = std::max(t, tCell);
      ++cellSteps;
      if (tCell > t && !col.cellObjects[k].empty() && !visit(t, tCell, col.cellObjects[k]))
        return WalkResult::Stopped;
      t = tCell;
      // Past the column's last cell along z the interval would end at tColumn: only a NaN gets here.
      if (t >= tColumn || k + zDir < 0 || k + zDir > int(splits.size())) break;
      k += zDir;
    }
    if (tEnd <= tS && tEnd <= tQ) return WalkResult::Finished;
    const int di = (tS == tColumn || tS <= t) && sDir != 0 ? sDir : 0;
    const int dj = (tQ == tColumn || tQ <= t) && qDir != 0 ? qDir : 0;
    // No face crossed yet the interval not ended: a NaN in t or tEnd. Moving nowhere, the walk would loop;
    // it ends as a NaN's tests end, having met nothing more.
    if (di == 0 && dj == 0) return WalkResult::Finished;
    const int ni = i + di, nj = j + dj;
    const bool leaves = ni < 0 || ni >= columnsX_ || nj < 0 || nj >= int(bounds_[1].size()) - 1;
    if (leaves) {
      exit = RegionExit{t, (ni < 0) ? -1 : (ni >= columnsX_ ? 1 : 0),
                        (nj < 0) ? -1 : (nj >= int(bounds_[1].size()) - 1 ? 1 : 0)};
      // Crossing a region corner while staying inside along one axis: move within first along that axis.
      if (exit.sStep == 0 && di != 0) i = ni;
      if (exit.qStep == 0 && dj != 0) j = nj;
      return WalkResult::Exited;
    }
    i = ni;
    j = nj;
  }
}

}  // namespace raycube::node
