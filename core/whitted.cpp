#include "core/whitted.h"

#include <cmath>

#include "core/precision.h"

namespace raycube::core {

Whitted::Whitted(const Scene& scene, ShadingOptions options) : Whitted(scene, options, scene.features()) {}

Whitted::Whitted(const Scene& scene, ShadingOptions options, const SceneFeatures& features)
    : scene_(scene), options_(options) {
  ambient_ = spdIntensity(scene.lights.size());
  for (const Light& light : scene.lights)
    lightIntensity_.push_back(light.hasColor ? light.color : Color(ambient_));
  sceneTransmits_ = features.transmission;
  spawnsSecondaryRays_ = options.maxDepth > 1 && (features.reflection || features.transmission);
}

template <class Real>
Vec3Of<Real> spawnOrigin(const Vec3Of<Real>& point, const Vec3Of<Real>& sideNormal, Real travelled) {
  const Vec3Of<Real> a = glm::abs(point);
  const Real magnitude = std::max({a.x, a.y, a.z, std::abs(travelled)});
  return point + (kSpawnOffsetRelativeOf<Real> * magnitude) * sideNormal;
}

template <class Real>
void Whitted::shadeMiss(const BasicTracedRay<Real>& ray, BasicRayOutcome<Real>& out) const {
  out.contributions.push_back(Contribution{ray.sample, Color(Vec3Of<Real>(scene_.background) * ray.coeff)});
}

template <class Real>
void Whitted::finishLightRay(const BasicTracedRay<Real>& ray, double transmission,
                             BasicRayOutcome<Real>& out) const {
  if (transmission > 0)
    out.contributions.push_back(Contribution{ray.sample, transmission * Color(ray.weight)});
}

namespace {

// A reflected or refracted ray (3.4): from `origin` along the unit `direction`, one level deeper than its
// parent, carrying its weight times `share`.
template <class Real>
BasicTracedRay<Real> secondaryRay(const BasicTracedRay<Real>& parent, RayKind kind,
                                  const Vec3Of<Real>& origin, const Vec3Of<Real>& direction, Real share) {
  BasicTracedRay<Real> spawned;
  spawned.ray.direction = direction;
  spawned.ray.origin = origin;
  spawned.ray.tMin = 0;
  spawned.ray.tMax = std::numeric_limits<Real>::infinity();
  spawned.coeff = parent.coeff * share;
  spawned.sample = parent.sample;
  spawned.depth = std::uint8_t(parent.depth + 1);
  spawned.kind = kind;
  return spawned;
}

}  // namespace

// The shading arithmetic is in the ray's precision Real: materials and lights are rounded to it.
template <class Real>
void Whitted::shadeHit(const BasicTracedRay<Real>& ray, const Hit& hit, BasicRayOutcome<Real>& out) const {
  using V = Vec3Of<Real>;
  const Object& object = scene_.objects[hit.object];
  const Material& m = scene_.materials[object.material];
  const Real kd = Real(m.kd);
  const Real tHit = Real(hit.t);
  const BasicSurfacePoint<Real> sp = surfaceAt(object, ray.ray, tHit);
  const V& d = ray.ray.direction;
  // The side of the surface the ray arrives on; normals are flipped to face it.
  const bool entering = glm::dot(sp.geometricNormal, d) < 0;
  const FacingHit<Real> at{sp.point, entering ? sp.geometricNormal : -sp.geometricNormal,
                           entering ? sp.shadingNormal : -sp.shadingNormal, tHit, entering};
  const V diffuse = kd * V(m.color);

  if (m.kd > 0)
    out.contributions.push_back(Contribution{ray.sample, Color(ray.coeff * Real(ambient_) * diffuse)});
  spawnLightRays(ray, m, at, diffuse, out);
  if (ray.depth >= options_.maxDepth) return;
  spawnSecondaryRays(ray, m, at, out);
}

// Section 3.4: a light ray towards each light the surface faces, carrying the Phong terms it would add.
template <class Real>
void Whitted::spawnLightRays(const BasicTracedRay<Real>& ray, const Material& m, const FacingHit<Real>& at,
                             const Vec3Of<Real>& diffuse, BasicRayOutcome<Real>& out) const {
  using V = Vec3Of<Real>;
  const Real ks = Real(m.ks);
  const V& n = at.shadingNormal;
  const V toViewer = -ray.ray.direction;
  const V lightRayOrigin = spawnOrigin(at.point, at.geometricNormal, at.t);
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const V lightPosition(scene_.lights[i].position);
    const V toLight = lightPosition - at.point;
    const Real distance = glm::length(toLight);
    if (distance == 0) continue;
    const V l = toLight / distance;
    const Real nl = glm::dot(n, l);
    if (nl <= 0) continue;  // SPD rule 10: no light ray when the normal faces away from the light
    V bracket = diffuse * nl;
    if (m.ks > 0) {
      const Real rv = glm::dot(2 * nl * n - l, toViewer);
      if (rv > 0) bracket += V(ks * std::pow(rv, Real(m.shine)));
    }
    const V weight = ray.coeff * V(lightIntensity_[i]) * bracket;
    if (weight == V(0)) continue;
    BasicTracedRay<Real> lightRay;
    lightRay.ray.origin = lightRayOrigin;
    const V fromOrigin = lightPosition - lightRayOrigin;
    lightRay.ray.tMax = glm::length(fromOrigin);
    lightRay.ray.direction = fromOrigin / lightRay.ray.tMax;
    lightRay.ray.tMin = 0;
    lightRay.weight = weight;
    lightRay.coeff = ray.coeff;
    lightRay.sample = ray.sample;
    lightRay.depth = ray.depth;
    lightRay.kind = RayKind::Light;
    lightRay.light = std::uint16_t(i);
    out.spawned.push_back(lightRay);
  }
}

// Section 3.4: the refracted ray (Snell's law) where the material transmits, and the reflected ray.
template <class Real>
void Whitted::spawnSecondaryRays(const BasicTracedRay<Real>& ray, const Material& m,
                                 const FacingHit<Real>& at, BasicRayOutcome<Real>& out) const {
  using V = Vec3Of<Real>;
  const Real ks = Real(m.ks), transmission = Real(m.transmission);
  const V& d = ray.ray.direction;
  const V& n = at.shadingNormal;
  Real reflectCoeff = ks;
  if (m.transmission > 0) {
    // Snell's law; eta is the ratio of indices across the surface in the ray's direction.
    const Real eta = at.entering ? Real(1.0 / m.ior) : Real(m.ior);
    const Real cosI = -glm::dot(n, d);
    const Real k = 1 - eta * eta * (1 - cosI * cosI);
    if (k < 0) {
      reflectCoeff += transmission;  // total internal reflection: the transmitted share is reflected
    } else if (worthSpawning(ray.coeff * transmission)) {
      out.spawned.push_back(
          secondaryRay(ray, RayKind::Refracted, spawnOrigin(at.point, -at.geometricNormal, at.t),
                       V(glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n)), transmission));
    }
  }
  if (reflectCoeff > 0 && worthSpawning(ray.coeff * reflectCoeff)) {
    const V toViewer = -d;
    out.spawned.push_back(secondaryRay(ray, RayKind::Reflected,
                                       spawnOrigin(at.point, at.geometricNormal, at.t),
                                       V(glm::normalize(d + 2 * glm::dot(n, toViewer) * n)), reflectCoeff));
  }
}

#define RAYCUBE_WHITTED_FOR(Real)                                                                           \
  template Vec3Of<Real> spawnOrigin(const Vec3Of<Real>&, const Vec3Of<Real>&, Real);                        \
  template void Whitted::shadeMiss(const BasicTracedRay<Real>&, BasicRayOutcome<Real>&) const;              \
  template void Whitted::finishLightRay(const BasicTracedRay<Real>&, double, BasicRayOutcome<Real>&) const; \
  template void Whitted::shadeHit(const BasicTracedRay<Real>&, const Hit&, BasicRayOutcome<Real>&) const;
RAYCUBE_WHITTED_FOR(float)
RAYCUBE_WHITTED_FOR(double)
#undef RAYCUBE_WHITTED_FOR

}  // namespace raycube::core
