#include "core/intersect.h"

#include <cmath>
#include <utility>

namespace raycube::core {
namespace {

// The smaller root in the open interval, from a numerically stable pair of roots.
double firstInInterval(double t0, double t1, double tMin, double tMax) {
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > tMin && t0 < tMax) return t0;
  if (t1 > tMin && t1 < tMax) return t1;
  return kInfinity;
}

// Sphere: the discriminant is formed from the perpendicular distance of the centre to the line
// (Haines et al., Ray Tracing Gems ch. 7), avoiding cancellation for small, far spheres.
double hitSphere(const Sphere& s, const Ray& ray, double tMax) {
  const Vec3 oc = ray.origin - s.center;
  const double b = -glm::dot(oc, ray.direction);
  const Vec3 f = oc + b * ray.direction;
  const double r2 = s.radius * s.radius;
  const double discriminant = r2 - glm::dot(f, f);
  if (discriminant < 0) return kInfinity;
  const double c = glm::dot(oc, oc) - r2;
  const double q = b + std::copysign(std::sqrt(discriminant), b);
  if (q == 0) return firstInInterval(0, 0, ray.tMin, tMax);
  return firstInInterval(c / q, q, ray.tMin, tMax);
}

struct TriangleHit {
  double t = kInfinity;
  double b0 = 0, b1 = 0, b2 = 0;  // barycentric weights of v0, v1, v2
};

// Watertight ray-triangle test (Woop, Benthin, Wald 2013): edges shared by two triangles are never missed.
bool hitTriangle(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Ray& ray, double tMax,
                 TriangleHit& out) {
  const Vec3& d = ray.direction;
  const Vec3 ad = glm::abs(d);
  const int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0) std::swap(kx, ky);
  const double sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0 / d[kz];
  const Vec3 a = v0 - ray.origin, b = v1 - ray.origin, c = v2 - ray.origin;
  const double ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const double bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const double cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
  const double u = cx * by - cy * bx;
  const double v = ax * cy - ay * cx;
  const double w = bx * ay - by * ax;
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
  const double det = u + v + w;
  if (det == 0) return false;
  const double tScaled = u * sz * a[kz] + v * sz * b[kz] + w * sz * c[kz];
  const double t = tScaled / det;
  if (!(t > ray.tMin && t < tMax)) return false;
  out = TriangleHit{t, u / det, v / det, w / det};
  return true;
}

// Polygons and patches are fans of triangles around vertex 0; the nearest fan triangle wins.
template <class Visit>
void forEachFanTriangle(const std::vector<Vec3>& vertices, Visit&& visit) {
  for (std::size_t i = 1; i + 1 < vertices.size(); ++i) visit(0u, i, i + 1);
}

TriangleHit hitFan(const std::vector<Vec3>& vertices, const Ray& ray, double tMax, std::size_t* corner) {
  TriangleHit best;
  forEachFanTriangle(vertices, [&](std::size_t i0, std::size_t i1, std::size_t i2) {
    TriangleHit h;
    if (hitTriangle(vertices[i0], vertices[i1], vertices[i2], ray, std::min(tMax, best.t), h)) {
      best = h;
      if (corner) *corner = i1;
    }
  });
  return best;
}

// Open cone or cylinder about the axis base->apex; radius varies linearly r(s) = r0 + k s, 0 <= s <= h.
struct ConeFrame {
  Vec3 axis;  // unit
  double height, slope;
};
ConeFrame frameOf(const Cone& c) {
  const Vec3 along = c.apex - c.base;
  const double h = glm::length(along);
  return ConeFrame{along / h, h, (c.apexRadius - c.baseRadius) / h};
}

double hitCone(const Cone& cone, const Ray& ray, double tMax) {
  const ConeFrame f = frameOf(cone);
  const Vec3 ob = ray.origin - cone.base;
  const double so = glm::dot(ob, f.axis), sd = glm::dot(ray.direction, f.axis);
  const Vec3 wo = ob - so * f.axis, wd = ray.direction - sd * f.axis;
  const double ro = cone.baseRadius + f.slope * so, rd = f.slope * sd;
  const double a = glm::dot(wd, wd) - rd * rd;
  const double b = 2 * (glm::dot(wo, wd) - ro * rd);
  const double c = glm::dot(wo, wo) - ro * ro;
  double t0, t1;
  if (std::abs(a) <= 1e-300) {
    if (b == 0) return kInfinity;
    t0 = t1 = -c / b;
  } else {
    const double discriminant = b * b - 4 * a * c;
    if (discriminant < 0) return kInfinity;
    const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
    t0 = q / a;
    t1 = q != 0 ? c / q : t0;
  }
  if (t0 > t1) std::swap(t0, t1);
  for (double t : {t0, t1}) {
    if (!(t > ray.tMin && t < tMax)) continue;
    const double s = so + t * sd;
    if (s >= 0 && s <= f.height && cone.baseRadius + f.slope * s >= 0) return t;
  }
  return kInfinity;
}

Vec3 polygonNormal(const std::vector<Vec3>& v) {
  return glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
}

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

}  // namespace

double nearestHit(const Object& object, const Ray& ray, double tMax) {
  return std::visit(Overloaded{[&](const Sphere& s) { return hitSphere(s, ray, tMax); },
                               [&](const Cone& c) { return hitCone(c, ray, tMax); },
                               [&](const Polygon& p) { return hitFan(p.vertices, ray, tMax, nullptr).t; },
                               [&](const Patch& p) { return hitFan(p.vertices, ray, tMax, nullptr).t; }},
                    object.shape);
}

SurfacePoint surfaceAt(const Object& object, const Ray& ray, double t) {
  SurfacePoint sp;
  sp.point = ray.at(t);
  std::visit(Overloaded{[&](const Sphere& s) {
                          sp.geometricNormal = glm::normalize(sp.point - s.center);
                          sp.shadingNormal = sp.geometricNormal;
                        },
                        [&](const Cone& c) {
                          const ConeFrame f = frameOf(c);
                          const Vec3 ob = sp.point - c.base;
                          const Vec3 w = ob - glm::dot(ob, f.axis) * f.axis;
                          const double len = glm::length(w);
                          const Vec3 radial = len > 0 ? w / len : Vec3(0);
                          sp.geometricNormal = glm::normalize(radial - f.slope * f.axis);
                          sp.shadingNormal = sp.geometricNormal;
                        },
                        [&](const Polygon& p) {
                          sp.geometricNormal = polygonNormal(p.vertices);
                          sp.shadingNormal = sp.geometricNormal;
                        },
                        [&](const Patch& p) {
                          sp.geometricNormal = polygonNormal(p.vertices);
                          std::size_t corner = 1;
                          Ray wide = ray;
                          wide.tMin = -kInfinity;
                          const TriangleHit h = hitFan(p.vertices, wide, kInfinity, &corner);
                          Vec3 n = p.normals[0];
                          if (h.t < kInfinity)
                            n = h.b0 * p.normals[0] + h.b1 * p.normals[corner] + h.b2 * p.normals[corner + 1];
                          const double len = glm::length(n);
                          n = len > 0 ? n / len : sp.geometricNormal;
                          sp.shadingNormal = glm::dot(n, sp.geometricNormal) < 0 ? -n : n;
                        }},
             object.shape);
  if (object.insideVisible) {
    sp.geometricNormal = -sp.geometricNormal;
    sp.shadingNormal = -sp.shadingNormal;
  }
  return sp;
}

Box boundsOf(const Object& object) {
  Box box;
  std::visit(Overloaded{[&](const Sphere& s) {
                          box.extend(s.center - Vec3(s.radius));
                          box.extend(s.center + Vec3(s.radius));
                        },
                        [&](const Cone& c) {
                          // Each end disc lies within a cube of its radius about its centre.
                          const double r0 = std::abs(c.baseRadius), r1 = std::abs(c.apexRadius);
                          box.extend(c.base - Vec3(r0));
                          box.extend(c.base + Vec3(r0));
                          box.extend(c.apex - Vec3(r1));
                          box.extend(c.apex + Vec3(r1));
                        },
                        [&](const Polygon& p) {
                          for (const Vec3& v : p.vertices) box.extend(v);
                        },
                        [&](const Patch& p) {
                          for (const Vec3& v : p.vertices) box.extend(v);
                        }},
             object.shape);
  return box.padded();
}

}  // namespace raycube::core
