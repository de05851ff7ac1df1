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

// The shading arithmetic is in the ray's precision Real: materials and lights are rounded to it.
template <class Real>
void Whitted::shadeHit(const BasicTracedRay<Real>& ray, const Hit& hit, BasicRayOutcome<Real>& out) const {
  using V = Vec3Of<Real>;
  const Object& object = scene_.objects[hit.object];
  const Material& m = scene_.materials[object.material];
  const Real kd = Real(m.kd), ks = Real(m.ks), transmission = Real(m.transmission);
  const Real tHit = Real(hit.t);
  const BasicSurfacePoint<Real> sp = surfaceAt(object, ray.ray, tHit);
  const V& d = ray.ray.direction;
  // The side of the surface the ray arrives on; normals are flipped to face it.
  const bool entering = glm::dot(sp.geometricNormal, d) < 0;
  const V ng = entering ? sp.geometricNormal : -sp.geometricNormal;
  V n = entering ? sp.shadingNormal : -sp.shadingNormal;
  const V diffuse = kd * V(m.color);

  if (m.kd > 0)
    out.contributions.push_back(Contribution{ray.sample, Color(ray.coeff * Real(ambient_) * diffuse)});

  const V toViewer = -d;
  const V lightRayOrigin = spawnOrigin(sp.point, ng, tHit);
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const V lightPosition(scene_.lights[i].position);
    const V toLight = lightPosition - sp.point;
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

  if (ray.depth >= options_.maxDepth) return;
  Real reflectCoeff = ks;
  if (m.transmission > 0) {
    // Snell's law; eta is the ratio of indices across the surface in the ray's direction.
    const Real eta = entering ? Real(1.0 / m.ior) : Real(m.ior);
    const Real cosI = -glm::dot(n, d);
    const Real k = 1 - eta * eta * (1 - cosI * cosI);
    if (k < 0) {
      reflectCoeff += transmission;  // total internal reflection: the transmitted share is reflected
    } else if (worthSpawning(ray.coeff * transmission)) {
      BasicTracedRay<Real> refracted;
      refracted.ray.direction = glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n);
      refracted.ray.origin = spawnOrigin(sp.point, -ng, tHit);
      refracted.ray.tMin = 0;
      refracted.ray.tMax = std::numeric_limits<Real>::infinity();
      refracted.coeff = ray.coeff * transmission;
      refracted.sample = ray.sample;
      refracted.depth = std::uint8_t(ray.depth + 1);
      refracted.kind = RayKind::Refracted;
      out.spawned.push_back(refracted);
    }
  }
  if (reflectCoeff > 0 && worthSpawning(ray.coeff * reflectCoeff)) {
    BasicTracedRay<Real> reflected;
    reflected.ray.direction = glm::normalize(d + 2 * glm::dot(n, toViewer) * n);
    reflected.ray.origin = spawnOrigin(sp.point, ng, tHit);
    reflected.ray.tMin = 0;
    reflected.ray.tMax = std::numeric_limits<Real>::infinity();
    reflected.coeff = ray.coeff * reflectCoeff;
    reflected.sample = ray.sample;
    reflected.depth = std::uint8_t(ray.depth + 1);
    reflected.kind = RayKind::Reflected;
    out.spawned.push_back(reflected);
  }
}

#define RAYCUBE_WHITTED_FOR(Real)                                                                         \
  template Vec3Of<Real> spawnOrigin(const Vec3Of<Real>&, const Vec3Of<Real>&, Real);                      \
  template void Whitted::shadeMiss(const BasicTracedRay<Real>&, BasicRayOutcome<Real>&) const;            \
  template void Whitted::finishLightRay(const BasicTracedRay<Real>&, double, BasicRayOutcome<Real>&) const; \
  template void Whitted::shadeHit(const BasicTracedRay<Real>&, const Hit&, BasicRayOutcome<Real>&) const;
RAYCUBE_WHITTED_FOR(float)
RAYCUBE_WHITTED_FOR(double)
#undef RAYCUBE_WHITTED_FOR

}  // namespace raycube::core
