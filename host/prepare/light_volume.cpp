#include "host/prepare/light_volume.h"

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

// A face of the pyramid in world space: the points p with n.p + d > 0 lie outside it.
struct Face {
  Vec3 n;
  double d;
};

struct Pyramid {
  LightFrame frame;
  double zMax, xMin, xMax, yMin, yMax;  // far face and the four side slopes x/z, y/z
  // In the light frame, outside the far face (z > zMax), behind the apex (z < 0), and beyond each slope
  // (x > xMax z, x < xMin z, y > yMax z, y < yMin z): six linear functions of the point, made world ones.
  Face faces[6];
  void placeFaces() {
    const LightFrame& f = frame;
    const Vec3 normals[6] = {
        f.z, -f.z, f.x - xMax * f.z, xMin * f.z - f.x, f.y - yMax * f.z, yMin * f.z - f.y};
    for (int i = 0; i < 6; ++i)
      faces[i] = Face{normals[i], -glm::dot(normals[i], f.s) - (i == 0 ? zMax : 0.0)};
  }
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
  Pyramid p{f, -core::kInfinity, core::kInfinity, -core::kInfinity, core::kInfinity, -core::kInfinity, {}};
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
  p.placeFaces();
  out = p;
  return true;
}

// A box misses the pyramid when all its corners lie outside one of the pyramid's five faces (or behind
// the apex): a conservative separating test, each face's least value over the box read at once from its
// centre and half extent.
bool boxMayMeetPyramid(const core::Box& box, const Pyramid& p) {
  const Vec3 centre = box.center(), half = 0.5 * box.extent();
  for (const Face& face : p.faces)
    if (glm::dot(face.n, centre) - glm::dot(glm::abs(face.n), half) + face.d > 0) return false;
  return true;
}

// Every corner strictly inside the pyramid, by a margin as large as any corner's: the box, and all it
// holds, lies inside.
bool boxInsidePyramid(const core::Box& box, const Pyramid& p) {
  const Vec3 centre = box.center(), half = 0.5 * box.extent();
  const double slack = core::kCellMarginRelative * (1 + glm::length(centre - p.frame.s) + glm::length(half));
  for (const Face& face : p.faces)
    if (!(glm::dot(face.n, centre) + glm::dot(glm::abs(face.n), half) + face.d < -slack)) return false;
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
