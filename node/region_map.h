#pragma once
// Which processor owns which pixel area (Priol & Bouatouch 3.1, 3.7.1): rectangles of samples that tile the
// screen — an R x C grid, or the leaves of a binary space partition — with their adjacency graph (figure 10:
// after a BSP a region can border several others on one face). A node uses it to name the owner of a point,
// the neighbour a ray enters and the next hop towards a processor that is not a neighbour; it knows
// nothing of how the host chose the areas.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "node/eye_frame_ray.h"
#include "node/ray_message.h"
#include "node/screen_grid.h"

namespace raycube::node {

class RegionMap {
 public:
  // Areas must tile [0, samplesX) x [0, samplesY) of `lines` without overlap. gridColumns > 0 says they
  // form a uniform grid of that many columns (routed along rows then columns, no routing table).
  RegionMap(std::vector<SampleRect> areas, const ScreenLines& lines, int gridColumns = 0);
  // The uniform R x C grid of 3.1, processors numbered row by row.
  static RegionMap grid(const std::vector<int>& columnStarts, const std::vector<int>& rowStarts,
                        const ScreenLines& lines);
  // Its areas, row by row.
  static std::vector<SampleRect> gridAreas(const std::vector<int>& columnStarts,
                                           const std::vector<int>& rowStarts);

  int processors() const { return int(areas_.size()); }
  int gridColumns() const { return gridColumns_; }  // > 0: built as a uniform grid of that many columns
  const ScreenLines& lines() const { return lines_; }
  const SampleRect& areaOf(int id) const { return areas_[id]; }
  ScreenRect screenRectOf(int id) const { return lines_.around(areas_[id]); }
  const std::vector<SampleRect>& areas() const { return areas_; }
  int ownerOfSample(int sx, int sy) const { return owner_[std::size_t(sy) * samplesX_ + sx]; }

  // The processor whose region holds the ray at t (front part only).
  int ownerAt(const EyeFrameRay& ray, double t) const;
  // Whether region `id` holds the ray at t (front part only): a quick test before the owner lookup.
  bool holds(int id, const EyeFrameRay& ray, double t) const {
    const ScreenRect r = screenRectOf(id);
    const double s = ray.screenAt(0, t), q = ray.screenAt(1, t);
    return s >= r.s0 && s < r.s1 && q >= r.q0 && q < r.q1;
  }
  // The processor a ray enters when it leaves region `id` at t through the faces (sStep, qStep).
  int ownerBeyond(int id, const EyeFrameRay& ray, double t, int sStep, int qStep) const;

  // Regions sharing a stretch of boundary with `id`, in increasing order, and which face of `id` they touch.
  const std::vector<int>& neighbours(int id) const { return neighbours_[id]; }
  // Where `neighbour` stands in neighbours(id): the index of the FIFO between the two.
  std::size_t neighbourSlot(int id, int neighbour) const {
    const std::vector<int>& n = neighbours_[id];
    return std::size_t(std::lower_bound(n.begin(), n.end(), neighbour) - n.begin());
  }
  Face faceToward(int id, int neighbour) const;
  // The neighbour of `from` on a shortest path to `to` in the adjacency graph.
  int nextHop(int from, int to) const;
  std::size_t adjacencyEdges() const;  // undirected

 private:
  std::vector<SampleRect> areas_;
  ScreenLines lines_;
  int samplesX_, samplesY_;
  std::vector<std::uint16_t> owner_;  // per sample
  std::vector<std::vector<int>> neighbours_;
  int gridColumns_ = 0;                 // > 0: a uniform grid, routed along rows then columns
  std::vector<std::uint16_t> nextHop_;  // otherwise: P x P next hops from breadth-first searches
};

}  // namespace raycube::node
