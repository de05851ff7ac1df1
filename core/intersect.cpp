#include "core/intersect.h"

#include <cmath>
#include <limits>
#include <span>
#include <utility>

#include "core/overloaded.h"
#include "core/polygon_outline.h"
#include "core/precision.h"

namespace raycube::core {
namespace {

template <class Real>
using V = Vec3Of<Real>;
template <class Real>
constexpr Real kNone = std::numeric_limits<Real>::infinity();

// The smaller root in the open interval, from a numerically stable pair of roots.
template <class Real>
Real firstInInterval(Real t0, Real t1, Real tMin, Real tMax) {
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > tMin && t0 < tMax) return t0;
  if (t1 > tMin && t1 < tMax) return t1;
  return kNone<Real>;
}

// Sphere: the discriminant is formed from the perpendicular distance of the centre to the line
// (Haines et al., Ray Tracing Gems ch. 7), avoiding cancellation for small, far spheres.
template <class Real>
Real hitSphere(const Sphere& s, const BasicRay<Real>& ray, Real tMax) {
  const V<Real> oc = ray.origin - V<Real>(s.center);
  const Real b = -glm::dot(oc, ray.direction);
  const V<Real> f = oc + b * ray.direction;
  const Real radius = Real(s.radius);
  const Real r2 = radius * radius;
  const Real discriminant = r2 - glm::dot(f, f);
  if (discriminant < 0) return kNone<Real>;
  const Real c = glm::dot(oc, oc) - r2;
  const Real q = b + std::copysign(std::sqrt(discriminant), b);
  if (q == 0) return firstInInterval(Real(0), Real(0), ray.tMin, tMax);
  return firstInInterval(c / q, q, ray.tMin, tMax);
}

template <class Real>
struct TriangleHit {
  Real t = kNone<Real>;
  Real b0 = 0, b1 = 0, b2 = 0;  // barycentric weights of v0, v1, v2
};

// Watertight ray-triangle test (Woop, Benthin, Wald 2013): edges shared by two triangles are never missed.
template <class Real>
bool hitTriangle(const V<Real>& v0, const V<Real>& v1, const V<Real>& v2, const BasicRay<Real>& ray,
                 Real tMax, TriangleHit<Real>& out) {
  const V<Real>& d = ray.direction;
  const V<Real> ad = glm::abs(d);
  const int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (d[kz] < 0) std::swap(kx, ky);
  const Real sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = Real(1) / d[kz];
  const V<Real> a = v0 - ray.origin, b = v1 - ray.origin, c = v2 - ray.origin;
  const Real ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
  const Real bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
  const Real cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
  const Real u = cx * by - cy * bx;
  const Real v = ax * cy - ay * cx;
  const Real w = bx * ay - by * ax;
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
  const Real det = u + v + w;
  if (det == 0) return false;
  const Real tScaled = u * sz * a[kz] + v * sz * b[kz] + w * sz * c[kz];
  const Real t = tScaled / det;
  if (!(t > ray.tMin && t < tMax)) return false;
  out = TriangleHit<Real>{t, u / det, v / det, w / det};
  return true;
}

// Polygons and patches are fans of triangles around vertex 0; the nearest fan triangle wins.
template <class Real>
TriangleHit<Real> hitFan(std::span<const Vec3> vertices, const BasicRay<Real>& ray, Real tMax,
                         std::size_t* corner) {
  TriangleHit<Real> best;
  const V<Real> v0(vertices[0]);
  for (std::size_t i = 1; i + 1 < vertices.size(); ++i) {
    TriangleHit<Real> h;
    if (hitTriangle(v0, V<Real>(vertices[i]), V<Real>(vertices[i + 1]), ray, std::min(tMax, best.t), h)) {
      best = h;
      if (corner) *corner = i;
    }
  }
  return best;
}

// A polygon of more than three corners: its plane, then the even-odd rule on its outline at the point met.
// The plane and t are in Real; the point's coordinates go to the outline as they are (a float converts
// exactly to double).
template <class Real>
Real hitOutline(const PolygonOutline& outline, const BasicRay<Real>& ray, Real tMax) {
  const V<Real> normal(outline.normal());
  const Real along = glm::dot(normal, ray.direction);
  if (along == 0) return kNone<Real>;
  const Real t = (Real(outline.offset()) - glm::dot(normal, ray.origin)) / along;
  if (!(t > ray.tMin && t < tMax)) return kNone<Real>;
  return outline.contains(Vec3(ray.at(t))) ? t : kNone<Real>;
}

template <class Real>
Real hitPolygon(const Polygon& polygon, const BasicRay<Real>& ray, Real tMax) {
  return polygon.outline ? hitOutline(*polygon.outline, ray, tMax)
                         : hitFan(polygon.vertices, ray, tMax, nullptr).t;
}

// Open cone or cylinder about the axis base->apex; radius varies linearly r(s) = r0 + k s, 0 <= s <= h.
template <class Real>
struct ConeFrame {
  V<Real> base, axis;  // axis: unit
  Real baseRadius, height, slope;
};
template <class Real>
ConeFrame<Real> frameOf(const Cone& c) {
  const V<Real> base(c.base), along = V<Real>(c.apex) - base;
  const Real h = glm::length(along);
  return ConeFrame<Real>{base, along / h, Real(c.baseRadius), h,
                         (Real(c.apexRadius) - Real(c.baseRadius)) / h};
}

// The quadratic is solved from the point of the ray nearest the cone's middle, tShift along it: from the
// ray's own origin, c = |wo|^2 - ro^2 cancels catastrophically when the origin lies far off compared with
// the radius (a float ray 23 units from a jacks cylinder of radius 0.019 "hit" it 6% of the radius outside
// its bounding box, which a BVH then culled: answers depending on the structure).
// Each end disc lies within a cube of its radius about its centre.
Box coneBounds(const Cone& c) {
  Box box;
  const double r0 = std::abs(c.baseRadius), r1 = std::abs(c.apexRadius);
  box.extend(c.base - Vec3(r0));
  box.extend(c.base + Vec3(r0));
  box.extend(c.apex - Vec3(r1));
  box.extend(c.apex + Vec3(r1));
  return box;
}

// Far along a long cone from its middle (a cylinder 37,708 units long and 0.07 wide, in float), even the
// shifted quadratic cancels to noise, and a root may lie off the cone and its box: a BVH culled what the
// reference's brute force returned. A root is a hit only inside the box every structure tests (padded as
// the BVH's for this precision), so every mode answers alike; on any real cone's surface it always is.
template <class Real>
bool withinConeBox(const Cone& cone, const V<Real>& point) {
  return coneBounds(cone).padded(kBoxPaddingRelativeOf<Real>).holds(Vec3(point));
}

template <class Real>
Real hitCone(const Cone& cone, const BasicRay<Real>& ray, Real tMax) {
  const ConeFrame<Real> f = frameOf<Real>(cone);
  const V<Real> fromBase = ray.origin - f.base;
  const Real sd = glm::dot(ray.direction, f.axis);
  const Real tShift = Real(0.5) * f.height * sd - glm::dot(fromBase, ray.direction);
  const V<Real> ob = fromBase + tShift * ray.direction;
  const Real so = glm::dot(ob, f.axis);
  const V<Real> wo = ob - so * f.axis, wd = ray.direction - sd * f.axis;
  const Real ro = f.baseRadius + f.slope * so, rd = f.slope * sd;
  const Real a = glm::dot(wd, wd) - rd * rd;
  const Real b = 2 * (glm::dot(wo, wd) - ro * rd);
  const Real c = glm::dot(wo, wo) - ro * ro;
  Real t0, t1;
  if (std::abs(a) <= std::numeric_limits<Real>::min()) {  // the ray runs along the cone's surface lines
    if (b == 0) return kNone<Real>;
    t0 = t1 = -c / b;
  } else {
    const Real discriminant = b * b - 4 * a * c;
    if (discriminant < 0) return kNone<Real>;
    const Real q = Real(-0.5) * (b + std::copysign(std::sqrt(discriminant), b));
    t0 = q / a;
    t1 = q != 0 ? c / q : t0;
  }
  if (t0 > t1) std::swap(t0, t1);
  for (Real tFromShift : {t0, t1}) {
    const Real t = tShift + tFromShift;
    if (!(t > ray.tMin && t < tMax)) continue;
    const Real s = so + tFromShift * sd;
    if (s >= 0 && s <= f.height && f.baseRadius + f.slope * s >= 0 && withinConeBox(cone, ray.at(t)))
      return t;
  }
  return kNone<Real>;
}

template <class Real>
V<Real> polygonNormal(std::span<const Vec3> v) {
  const V<Real> v0(v[0]);
  return glm::normalize(glm::cross(V<Real>(v[1]) - v0, V<Real>(v[2]) - v0));
}

}  // namespace

template <class Real>
Real nearestHit(const Object& object, const BasicRay<Real>& ray, std::type_identity_t<Real> tMax) {
  return std::visit(Overloaded{[&](const Sphere& s) { return hitSphere(s, ray, tMax); },
                               [&](const Cone& c) { return hitCone(c, ray, tMax); },
                               [&](const Polygon& p) { return hitPolygon(p, ray, tMax); },
                               [&](const Patch& p) { return hitFan(p.vertices, ray, tMax, nullptr).t; }},
                    object.shape);
}

template <class Real>
BasicSurfacePoint<Real> surfaceAt(const Object& object, const BasicRay<Real>& ray,
                                  std::type_identity_t<Real> t) {
  BasicSurfacePoint<Real> sp;
  sp.point = ray.at(t);
  std::visit(Overloaded{[&](const Sphere& s) {
                          sp.geometricNormal = glm::normalize(sp.point - V<Real>(s.center));
                          sp.shadingNormal = sp.geometricNormal;
                        },
                        [&](const Cone& c) {
                          const ConeFrame<Real> f = frameOf<Real>(c);
                          const V<Real> ob = sp.point - f.base;
                          const V<Real> w = ob - glm::dot(ob, f.axis) * f.axis;
                          const Real len = glm::length(w);
                          const V<Real> radial = len > 0 ? w / len : V<Real>(0);
                          sp.geometricNormal = glm::normalize(radial - f.slope * f.axis);
                          sp.shadingNormal = sp.geometricNormal;
                        },
                        [&](const Polygon& p) {
                          sp.geometricNormal = polygonNormal<Real>(p.vertices);
                          sp.shadingNormal = sp.geometricNormal;
                        },
                        [&](const Patch& p) {
                          sp.geometricNormal = polygonNormal<Real>(p.vertices);
                          std::size_t corner = 1;
                          BasicRay<Real> wide = ray;
                          wide.tMin = -kNone<Real>;
                          const TriangleHit<Real> h = hitFan(p.vertices, wide, kNone<Real>, &corner);
                          V<Real> n(p.normals[0]);
                          if (h.t < kNone<Real>)
                            n = h.b0 * V<Real>(p.normals[0]) + h.b1 * V<Real>(p.normals[corner]) +
                                h.b2 * V<Real>(p.normals[corner + 1]);
                          const Real len = glm::length(n);
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

template float nearestHit(const Object&, const BasicRay<float>&, float);
template double nearestHit(const Object&, const BasicRay<double>&, double);
template BasicSurfacePoint<float> surfaceAt(const Object&, const BasicRay<float>&, float);
template BasicSurfacePoint<double> surfaceAt(const Object&, const BasicRay<double>&, double);

Box boundsOf(const Object& object, double paddingRelative) {
  Box box;
  std::visit(
      Overloaded{[&](const Sphere& s) {
                   box.extend(s.center - Vec3(s.radius));
                   box.extend(s.center + Vec3(s.radius));
                 },
                 [&](const Cone& c) { box = coneBounds(c); },
                 [&](const Polygon& p) { forEachBoundingPoint(p, [&](const Vec3& v) { box.extend(v); }); },
                 [&](const Patch& p) {
                   for (const Vec3& v : p.vertices) box.extend(v);
                 }},
      object.shape);
  return box.padded(paddingRelative);
}

}  // namespace raycube::core
