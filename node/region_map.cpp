#include "node/region_map.h"

#include <algorithm>
#include <deque>
#include <stdexcept>

namespace raycube::node {
namespace {

// Do two rectangles share a stretch of boundary of positive length?
bool adjacent(const SampleRect& a, const SampleRect& b) {
  const bool sideBySide = (a.x1 == b.x0 || b.x1 == a.x0) && std::min(a.y1, b.y1) > std::max(a.y0, b.y0);
  const bool stacked = (a.y1 == b.y0 || b.y1 == a.y0) && std::min(a.x1, b.x1) > std::max(a.x0, b.x0);
  return sideBySide || stacked;
}

}  // namespace

RegionMap::RegionMap(std::vector<SampleRect> areas, const ScreenLines& lines, int gridColumns)
    : areas_(std::move(areas)),
      lines_(lines),
      samplesX_(lines.samples(0)),
      samplesY_(lines.samples(1)),
      gridColumns_(gridColumns) {
  if (areas_.empty() || areas_.size() > UINT16_MAX)
    throw std::invalid_argument("RegionMap: bad processor count");
  owner_.assign(std::size_t(samplesX_) * samplesY_, UINT16_MAX);
  for (std::size_t id = 0; id < areas_.size(); ++id) {
    const SampleRect& a = areas_[id];
    if (a.x0 < 0 || a.y0 < 0 || a.x1 > samplesX_ || a.y1 > samplesY_ || a.count() <= 0)
      throw std::invalid_argument("RegionMap: an area lies outside the sample grid or is empty");
    for (int y = a.y0; y < a.y1; ++y)
      for (int x = a.x0; x < a.x1; ++x) {
        std::uint16_t& slot = owner_[std::size_t(y) * samplesX_ + x];
        if (slot != UINT16_MAX) throw std::invalid_argument("RegionMap: areas overlap");
        slot = std::uint16_t(id);
      }
  }
  if (std::find(owner_.begin(), owner_.end(), UINT16_MAX) != owner_.end())
    throw std::invalid_argument("RegionMap: areas leave samples uncovered");
  const int p = processors();
  neighbours_.resize(p);
  for (int i = 0; i < p; ++i)
    for (int j = i + 1; j < p; ++j)
      if (adjacent(areas_[i], areas_[j])) {
        neighbours_[i].push_back(j);
        neighbours_[j].push_back(i);
      }
  if (gridColumns_ > 0) return;
  // Breadth-first search from every destination: next hop towards it from each processor.
  nextHop_.assign(std::size_t(p) * p, UINT16_MAX);
  for (int to = 0; to < p; ++to) {
    std::deque<int> frontier{to};
    nextHop_[std::size_t(to) * p + to] = std::uint16_t(to);
    while (!frontier.empty()) {
      const int at = frontier.front();
      frontier.pop_front();
      for (int n : neighbours_[at]) {
        std::uint16_t& hop = nextHop_[std::size_t(n) * p + to];
        if (hop != UINT16_MAX) continue;
        hop = std::uint16_t(at);  // from n, step to `at`, which is one hop closer to `to`
        frontier.push_back(n);
      }
    }
  }
}

std::vector<SampleRect> RegionMap::gridAreas(const std::vector<int>& columnStarts,
                                             const std::vector<int>& rowStarts) {
  std::vector<SampleRect> areas;
  for (std::size_t r = 0; r + 1 < rowStarts.size(); ++r)
    for (std::size_t c = 0; c + 1 < columnStarts.size(); ++c)
      areas.push_back(SampleRect{columnStarts[c], columnStarts[c + 1], rowStarts[r], rowStarts[r + 1]});
  return areas;
}

RegionMap RegionMap::grid(const std::vector<int>& columnStarts, const std::vector<int>& rowStarts,
                          const ScreenLines& lines) {
  return RegionMap(gridAreas(columnStarts, rowStarts), lines, int(columnStarts.size()) - 1);
}

int RegionMap::ownerAt(const EyeFrameRay& ray, double t) const {
  return ownerOfSample(lines_.sampleIndex(0, ray.screenAt(0, t), 0, samplesX_),
                       lines_.sampleIndex(1, ray.screenAt(1, t), 0, samplesY_));
}

int RegionMap::ownerBeyond(int id, const EyeFrameRay& ray, double t, int sStep, int qStep) const {
  // A uniform grid's regions are its cells, numbered row by row: across a face or a corner, the next cell
  // (no region lies beyond the screen's edges, which are at infinity).
  if (gridColumns_ > 0) return id + sStep + qStep * gridColumns_;
  // Along a face not crossed the ray is still within the region's range of samples.
  const SampleRect& a = areas_[id];
  const int column = sStep > 0   ? a.x1
                     : sStep < 0 ? a.x0 - 1
                                 : lines_.sampleIndex(0, ray.screenAt(0, t), a.x0, a.x1);
  const int row = qStep > 0   ? a.y1
                  : qStep < 0 ? a.y0 - 1
                              : lines_.sampleIndex(1, ray.screenAt(1, t), a.y0, a.y1);
  // Across a face: one of the few neighbours, whose areas are at hand (the owner table is a megabyte at
  // 512 x 512, and missing the cache in it cost a visible share of a run). Through a corner: the table.
  for (int n : neighbours_[id]) {
    const SampleRect& b = areas_[n];
    if (column >= b.x0 && column < b.x1 && row >= b.y0 && row < b.y1) return n;
  }
  return ownerOfSample(column, row);
}

Face RegionMap::faceToward(int id, int neighbour) const {
  const SampleRect& a = areas_[id];
  const SampleRect& b = areas_[neighbour];
  if (b.x1 == a.x0) return Face::Left;
  if (b.x0 == a.x1) return Face::Right;
  return b.y1 == a.y0 ? Face::Up : Face::Down;
}

int RegionMap::nextHop(int from, int to) const {
  if (gridColumns_ > 0) {
    // Dimension-order routing on the 2D array: along the row first, then along the column.
    const int fc = from % gridColumns_, tc = to % gridColumns_;
    if (tc != fc) return from + (tc > fc ? 1 : -1);
    return from + (to > from ? gridColumns_ : -gridColumns_);
  }
  return nextHop_[std::size_t(from) * processors() + to];
}

std::size_t RegionMap::adjacencyEdges() const {
  std::size_t twice = 0;
  for (const auto& n : neighbours_) twice += n.size();
  return twice / 2;
}

}  // namespace raycube::node
