#include "core/whitted.h"

#include <cmath>

#include "core/tolerances.h"

namespace raycube::core {

Whitted::Whitted(const Scene& scene, ShadingOptions options) : scene_(scene), options_(options) {
  const double count = double(scene.lights.size());
  ambient_ = count > 0 ? std::sqrt(count) / (2 * count) : 0.0;
  for (const Light& light : scene.lights)
    lightIntensity_.push_back(light.hasColor ? light.color : Color(ambient_));
  sceneTransmits_ = scene.features().transmission;
}

Vec3 spawnOrigin(const Vec3& point, const Vec3& sideNormal, double travelled) {
  const Vec3 a = glm::abs(point);
  const double magnitude = std::max({a.x, a.y, a.z, std::abs(travelled)});
  return point + (kSpawnOffsetRelative * magnitude) * sideNormal;
}

void Whitted::shadeMiss(const TracedRay& ray, RayOutcome& out) const {
  out.contributions.push_back(Contribution{ray.sample, ray.coeff * scene_.background});
}

void Whitted::finishShadow(const TracedRay& ray, double transmission, RayOutcome& out) const {
  if (transmission > 0) out.contributions.push_back(Contribution{ray.sample, transmission * ray.weight});
}

void Whitted::shadeHit(const TracedRay& ray, const Hit& hit, RayOutcome& out) const {
  const Object& object = scene_.objects[hit.object];
  const Material& m = scene_.materials[object.material];
  const SurfacePoint sp = surfaceAt(object, ray.ray, hit.t);
  const Vec3& d = ray.ray.direction;
  // The side of the surface the ray arrives on; normals are flipped to face it.
  const bool entering = glm::dot(sp.geometricNormal, d) < 0;
  const Vec3 ng = entering ? sp.geometricNormal : -sp.geometricNormal;
  Vec3 n = entering ? sp.shadingNormal : -sp.shadingNormal;
  const Color diffuse = m.kd * m.color;

  if (m.kd > 0) out.contributions.push_back(Contribution{ray.sample, ray.coeff * ambient_ * diffuse});

  const Vec3 toViewer = -d;
  const Vec3 shadowOrigin = spawnOrigin(sp.point, ng, hit.t);
  for (std::size_t i = 0; i < scene_.lights.size(); ++i) {
    const Vec3 toLight = scene_.lights[i].position - sp.point;
    const double distance = glm::length(toLight);
    if (distance == 0) continue;
    const Vec3 l = toLight / distance;
    const double nl = glm::dot(n, l);
    if (nl <= 0) continue;  // SPD rule 10: no shadow ray when the normal faces away from the light
    Color bracket = diffuse * nl;
    if (m.ks > 0) {
      const double rv = glm::dot(2 * nl * n - l, toViewer);
      if (rv > 0) bracket += Color(m.ks * std::pow(rv, m.shine));
    }
    const Color weight = ray.coeff * lightIntensity_[i] * bracket;
    if (weight == Color(0)) continue;
    TracedRay shadow;
    shadow.ray.origin = shadowOrigin;
    const Vec3 fromOrigin = scene_.lights[i].position - shadowOrigin;
    shadow.ray.tMax = glm::length(fromOrigin);
    shadow.ray.direction = fromOrigin / shadow.ray.tMax;
    shadow.ray.tMin = 0;
    shadow.weight = weight;
    shadow.coeff = ray.coeff;
    shadow.sample = ray.sample;
    shadow.depth = ray.depth;
    shadow.kind = RayKind::Shadow;
    shadow.light = std::uint16_t(i);
    out.spawned.push_back(shadow);
  }

  if (ray.depth >= options_.maxDepth) return;
  double reflectCoeff = m.ks;
  if (m.transmittance > 0) {
    // Snell's law; eta is the ratio of indices across the surface in the ray's direction.
    const double eta = entering ? 1.0 / m.ior : m.ior;
    const double cosI = -glm::dot(n, d);
    const double k = 1 - eta * eta * (1 - cosI * cosI);
    if (k < 0) {
      reflectCoeff += m.transmittance;  // total internal reflection: the transmitted share is reflected
    } else if (worthSpawning(ray.coeff * m.transmittance)) {
      TracedRay refracted;
      refracted.ray.direction = glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n);
      refracted.ray.origin = spawnOrigin(sp.point, -ng, hit.t);
      refracted.ray.tMin = 0;
      refracted.ray.tMax = kInfinity;
      refracted.coeff = ray.coeff * m.transmittance;
      refracted.sample = ray.sample;
      refracted.depth = std::uint8_t(ray.depth + 1);
      refracted.kind = RayKind::Refracted;
      out.spawned.push_back(refracted);
    }
  }
  if (reflectCoeff > 0 && worthSpawning(ray.coeff * reflectCoeff)) {
    TracedRay reflected;
    reflected.ray.direction = glm::normalize(d + 2 * glm::dot(n, toViewer) * n);
    reflected.ray.origin = spawnOrigin(sp.point, ng, hit.t);
    reflected.ray.tMin = 0;
    reflected.ray.tMax = kInfinity;
    reflected.coeff = ray.coeff * reflectCoeff;
    reflected.sample = ray.sample;
    reflected.depth = std::uint8_t(ray.depth + 1);
    reflected.kind = RayKind::Reflected;
    out.spawned.push_back(reflected);
  }
}

}  // namespace raycube::core
