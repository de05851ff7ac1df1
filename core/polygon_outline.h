#pragma once
// The inside of a polygon, concave or convex, answered in time about constant in its vertex count. NFF's
// "p" may be concave (SPD gears writes its gear faces as 144-vertex outlines with the teeth cut in); a fan of
// triangles around vertex 0 covers such a polygon's notches too, and tests every vertex. The outline instead
// holds the polygon in its own plane, dropped onto the two axes its normal is least along, with its edges
// sorted into horizontal bands of equal height: a point's band lists every edge whose height range contains
// the point's, and the even-odd rule (the crossing number of a half-line towards +x, as POV-Ray's polygon)
// decides on those edges only.
//
// Exact: the answer is that of the crossing test over all the edges, on every point. Band lookup and edge
// ranges go through the same monotone function of height, so an edge that spans a point's height is always
// in its band; edges are kept lower end first, so an edge two polygons share gives both the same crossing
// abscissa and a point on it belongs to exactly one of them.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec.h"

namespace raycube::core {

class PolygonOutline {
 public:
  // vertices: a planar polygon of at least 3 vertices, in order; its plane must be well defined.
  explicit PolygonOutline(const std::vector<Vec3>& vertices);

  // The plane: dot(normal(), p) == offset() on the polygon; normal is unit (Newell's, robust for concave
  // outlines), its sign following the vertex order.
  const Vec3& normal() const { return normal_; }
  double offset() const { return offset_; }

  // The point of the plane over v's plane coordinates. Hits lie on the plane, so when the vertices leave
  // it (an NFF file's rounding, or worse) the box of these points, not of the vertices, bounds them.
  Vec3 onPlane(const Vec3& v) const;

  // Whether a point of the plane lies inside by the even-odd rule (a point of the polygon's plane; the
  // component along the dropped axis is ignored).
  bool contains(const Vec3& point) const;
  // The same, on the plane's own two coordinates (see planeCoordinates).
  bool contains(double x, double y) const;
  void planeCoordinates(const Vec3& point, double& x, double& y) const {
    x = point[xAxis_];
    y = point[yAxis_];
  }

  std::size_t bandCount() const { return bandStart_.size() - 1; }
  // Edges a point in the given band is tested against (for tests and benchmarks).
  std::size_t edgesInBand(std::size_t band) const { return bandStart_[band + 1] - bandStart_[band]; }

 private:
  struct Edge {  // lower end first: y0 < y1; x = x0 + (y - y0) * slope
    double x0, y0, y1, slope;
    bool crossedRightOf(double x, double y) const { return y0 <= y && y < y1 && x < x0 + (y - y0) * slope; }
  };
  std::size_t bandOf(double y) const;

  Vec3 normal_{0, 0, 1};
  double offset_ = 0;
  int xAxis_ = 0, yAxis_ = 1;
  double xMin_ = 0, xMax_ = 0, yMin_ = 0, yMax_ = 0;
  double bandsPerUnit_ = 0;
  std::vector<std::uint32_t> bandStart_;  // edges of band b: edges_[bandStart_[b] .. bandStart_[b + 1])
  std::vector<Edge> edges_;               // each edge once per band it spans
};

}  // namespace raycube::core
