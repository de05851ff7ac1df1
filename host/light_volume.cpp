#include "host/light_volume.h"

#include <algorithm>
#include <cmath>

#include "core/tolerances.h"

namespace raycube::host {

using node::LightRayMode;
using node::LightSources;
namespace {

using core::Vec3;

// Figure 13: the light frame (S, X_l, Y_l, Z_l), Z_l through the centre of gravity C of the sources.
struct LightFrame {
  Vec3 s, x, y, z;
  Vec3 to(const Vec3& p) const {
    const Vec3 d = p - s;
    return Vec3(glm::dot(d, x), glm::dot(d, y), glm::dot(d, z));
  }
};

struct Pyramid {
  LightFrame frame;
  double zMax, xMin, xMax, yMin, yMax;  // far face and the four side slopes x/z, y/z
};

bool buildPyramid(const Vec3& light, const LightSources& sources, Pyramid& out) {
  Vec3 c(0);
  for (const Vec3& v : sources.corners) c += v;
  c /= double(sources.corners.size());
  const Vec3 sc = c - light;
  const double distance = glm::length(sc);
  if (distance == 0) return false;
  LightFrame f;
  f.s = light;
  f.z = sc / distance;
  // X_l = SV ^ SC for a vertex V off the axis (any perpendicular works: the pyramid is fitted after).
  Vec3 axis = glm::cross(f.z, Vec3(1, 0, 0));
  if (glm::length(axis) < 0.5) axis = glm::cross(f.z, Vec3(0, 1, 0));
  f.x = glm::normalize(axis);
  f.y = glm::cross(f.x, f.z);
  Pyramid p{f, -core::kInfinity, core::kInfinity, -core::kInfinity, core::kInfinity, -core::kInfinity};
  const double scale = distance + glm::length(sources.eyeBox.extent());
  for (const Vec3& v : sources.corners) {
    const Vec3 l = f.to(v);
    if (l.z <= core::kCellMarginRelative * scale) return false;  // the light is among the sources
    p.zMax = std::max(p.zMax, l.z);
    p.xMin = std::min(p.xMin, l.x / l.z);
    p.xMax = std::max(p.xMax, l.x / l.z);
    p.yMin = std::min(p.yMin, l.y / l.z);
    p.yMax = std::max(p.yMax, l.y / l.z);
  }
  const double slack =
      core::kCellMarginRelative *
      (1 + std::max({std::abs(p.xMin), std::abs(p.xMax), std::abs(p.yMin), std::abs(p.yMax)}));
  p.xMin -= slack;
  p.yMin -= slack;
  p.xMax += slack;
  p.yMax += slack;
  p.zMax += core::kCellMarginRelative * scale;
  out = p;
  return true;
}

// A box misses the pyramid when all its corners lie outside one of the pyramid's five faces (or behind
// the apex): a conservative separating test.
bool boxMayMeetPyramid(const core::Box& box, const Pyramid& p) {
  bool outside[6] = {true, true, true, true, true, true};
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 l = p.frame.to(Vec3(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                                   corner & 4 ? box.hi.z : box.lo.z));
    outside[0] &= l.z > p.zMax;
    outside[1] &= l.z < 0;
    outside[2] &= l.x > p.xMax * l.z;
    outside[3] &= l.x < p.xMin * l.z;
    outside[4] &= l.y > p.yMax * l.z;
    outside[5] &= l.y < p.yMin * l.z;
  }
  return !(outside[0] || outside[1] || outside[2] || outside[3] || outside[4] || outside[5]);
}

// Every corner strictly inside the pyramid, by a margin: the box, and all it holds, lies inside.
bool boxInsidePyramid(const core::Box& box, const Pyramid& p) {
  const double m = core::kCellMarginRelative;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 l = p.frame.to(Vec3(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                                   corner & 4 ? box.hi.z : box.lo.z));
    const double slack = m * (1 + glm::length(l));
    if (!(l.z > slack && l.z < p.zMax - slack && l.x < p.xMax * l.z - slack && l.x > p.xMin * l.z + slack &&
          l.y < p.yMax * l.z - slack && l.y > p.yMin * l.z + slack))
      return false;
  }
  return true;
}

// Figure 12: the cone from the light around the sources' bounding sphere, truncated by the plane beyond
// the sphere; an object is kept when its bounding sphere meets the truncated cone.
struct Cone {
  Vec3 apex, axis;
  double sinHalf, cosHalf, length;
};

bool buildCone(const Vec3& light, const LightSources& sources, Cone& out) {
  Vec3 c(0);
  for (const Vec3& v : sources.corners) c += v;
  c /= double(sources.corners.size());
  double radius = 0;
  for (const Vec3& v : sources.corners) radius = std::max(radius, glm::length(v - c));
  radius *= 1 + core::kCellMarginRelative;
  const Vec3 sc = c - light;
  const double distance = glm::length(sc);
  if (distance <= radius) return false;  // the light is inside the sphere
  out.apex = light;
  out.axis = sc / distance;
  out.sinHalf = radius / distance;
  out.cosHalf = std::sqrt(1 - out.sinHalf * out.sinHalf);
  out.length = distance + radius;
  return true;
}

bool sphereMayMeetCone(const Vec3& centre, double r, const Cone& cone) {
  const Vec3 d = centre - cone.apex;
  const double along = glm::dot(d, cone.axis);
  if (along < -r || along > cone.length + r) return false;  // behind the light or beyond the far plane
  const double across = glm::length(d - along * cone.axis);
  // Distance from the centre to the cone's surface line in the axial plane (Amanatides 1984).
  return across * cone.cosHalf - along * cone.sinHalf <= r;
}

}  // namespace

std::vector<std::uint32_t> objectsInLightVolume(LightRayMode mode, const core::Vec3& light,
                                                const LightSources& sources, const BoxTree& objects) {
  if (sources.eyeBox.empty() || mode == LightRayMode::Messages) return {};
  auto every = [](const core::Box&) { return true; };
  if (mode == LightRayMode::Pyramid) {
    Pyramid pyramid;
    if (!buildPyramid(light, sources, pyramid)) return objects.query(every);
    return objects.query([&](const core::Box& b) { return boxMayMeetPyramid(b, pyramid); },
                         [&](const core::Box& b) { return boxInsidePyramid(b, pyramid); });
  }
  Cone cone;
  if (!buildCone(light, sources, cone)) return objects.query(every);
  return objects.query(
      [&](const core::Box& b) { return sphereMayMeetCone(b.center(), 0.5 * glm::length(b.extent()), cone); });
}

}  // namespace raycube::host
