#include "core/polygon_outline.h"

#include <algorithm>
#include <cmath>

namespace raycube::core {
namespace {

// Newell's normal: the polygon's area vector, exact in sign for any simple outline, convex or not.
Vec3 newellNormal(const std::vector<Vec3>& v) {
  Vec3 n(0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3& a = v[i];
    const Vec3& b = v[(i + 1) % v.size()];
    n += Vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  return n;
}

// The axis the normal is most along: dropping it projects the polygon with the least distortion.
int droppedAxis(const Vec3& normal) {
  const Vec3 a = glm::abs(normal);
  return a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
}

struct Point2 {
  double x, y;
};

std::vector<Point2> projected(const std::vector<Vec3>& vertices, int xAxis, int yAxis) {
  std::vector<Point2> points;
  points.reserve(vertices.size());
  for (const Vec3& v : vertices) points.push_back({v[xAxis], v[yAxis]});
  return points;
}

}  // namespace

PolygonOutline::PolygonOutline(const std::vector<Vec3>& vertices) {
  normal_ = glm::normalize(newellNormal(vertices));
  for (const Vec3& v : vertices) offset_ += glm::dot(normal_, v);
  offset_ /= static_cast<double>(vertices.size());
  const int dropped = droppedAxis(normal_);
  xAxis_ = (dropped + 1) % 3;
  yAxis_ = (dropped + 2) % 3;

  const std::vector<Point2> points = projected(vertices, xAxis_, yAxis_);
  xMin_ = xMax_ = points[0].x;
  yMin_ = yMax_ = points[0].y;
  for (const Point2& p : points) {
    xMin_ = std::min(xMin_, p.x), xMax_ = std::max(xMax_, p.x);
    yMin_ = std::min(yMin_, p.y), yMax_ = std::max(yMax_, p.y);
  }
  // Edges that can be crossed (horizontal ones never straddle a height), lower end first.
  std::vector<Edge> crossable;
  for (std::size_t i = 0; i < points.size(); ++i) {
    Point2 a = points[i], b = points[(i + 1) % points.size()];
    if (a.y == b.y) continue;
    if (a.y > b.y) std::swap(a, b);
    crossable.push_back(Edge{a.x, a.y, b.y, (b.x - a.x) / (b.y - a.y)});
  }
  // About one band per edge: a band then holds a few edges, the outline's crossings at that height.
  const std::size_t bands = std::max<std::size_t>(1, crossable.size());
  bandsPerUnit_ = yMax_ > yMin_ ? static_cast<double>(bands) / (yMax_ - yMin_) : 0;
  bandStart_.assign(bands + 1, 0);
  for (const Edge& e : crossable)
    for (std::size_t b = bandOf(e.y0); b <= bandOf(e.y1); ++b) ++bandStart_[b + 1];
  for (std::size_t b = 0; b < bands; ++b) bandStart_[b + 1] += bandStart_[b];
  edges_.resize(bandStart_[bands]);
  std::vector<std::uint32_t> filled(bandStart_.begin(), bandStart_.end() - 1);
  for (const Edge& e : crossable)
    for (std::size_t b = bandOf(e.y0); b <= bandOf(e.y1); ++b) edges_[filled[b]++] = e;
}

Vec3 PolygonOutline::onPlane(const Vec3& v) const {
  const int dropped = 3 - xAxis_ - yAxis_;
  Vec3 p = v;
  p[dropped] = (offset_ - normal_[xAxis_] * v[xAxis_] - normal_[yAxis_] * v[yAxis_]) / normal_[dropped];
  return p;
}

// Monotone in y (a subtraction and a product by positive constants, rounded, then floored and clamped), so
// y0 <= y <= y1 puts y's band between y0's and y1's.
std::size_t PolygonOutline::bandOf(double y) const {
  const double band = std::floor((y - yMin_) * bandsPerUnit_);
  return static_cast<std::size_t>(std::clamp(band, 0.0, static_cast<double>(bandCount() - 1)));
}

bool PolygonOutline::contains(double x, double y) const {
  if (!(y >= yMin_ && y < yMax_)) return false;  // no edge spans y (and NaN is outside)
  const std::size_t band = bandOf(y);
  bool inside = false;
  for (std::uint32_t i = bandStart_[band]; i < bandStart_[band + 1]; ++i)
    inside ^= edges_[i].crossedRightOf(x, y);
  return inside;
}

bool PolygonOutline::contains(const Vec3& point) const {
  double x, y;
  planeCoordinates(point, x, y);
  return contains(x, y);
}

}  // namespace raycube::core
