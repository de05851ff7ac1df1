#pragma once
// The Whitted illumination model exactly as the SPD testing rules specify, in the contribution form of
// Priol & Bouatouch section 3.4: every sample's colour is a sum of (Ks/Kt product) x (local term)
// pieces, so no intensity ever travels back along a ray's path and the host can add them in any order.
//
// At a hit with material (C, Kd, Ks, Shine, T, ior), for a ray carrying coeff:
//   ambient     coeff * A * Kd * C                                   sent at once
//   per light   coeff * I * (Kd * C * (N.L) + Ks * max(0, R.V)^Shine) * transmission(P -> light)
//               a light ray per light with N.L > 0 carries the bracket as its weight
//   reflection  a ray with coeff * Ks when Ks > 0 and depth < maxDepth
//   refraction  a ray with coeff * T when T > 0 and depth < maxDepth (Snell); on total internal reflection
//               no refraction ray, and the reflected ray carries coeff * (Ks + T) so no energy is lost
// A ray that hits nothing contributes coeff * background. I = A = sqrt(L) / (2 L) for L lights, unless the
// file gives the light a colour; A = 0.5 without lights (spdIntensity). N faces the incoming ray.
#include <vector>

#include "core/intersect.h"
#include "core/ray.h"
#include "core/scene.h"

namespace raycube::core {

struct ShadingOptions {
  int maxDepth = 5;  // SPD rule 7: the eye ray has depth 1
  // Adaptive tree depth (Hall & Greenberg 1983): no reflected or refracted ray whose cumulated Ks/Kt weight
  // (per sample, so independent of the rays per sample) falls below this. 0, the SPD rule, spawns them all.
  double minWeight = 0;
  int raysPerSample = 1;  // eye rays per sample: each starts with coeff 1 / raysPerSample
};

// What one ray produces: contributions for the host and rays for the tree. Reused to avoid allocation.
template <class Real>
struct BasicRayOutcome {
  std::vector<Contribution> contributions;
  std::vector<BasicTracedRay<Real>> spawned;
  void clear() {
    contributions.clear();
    spawned.clear();
  }
};
using RayOutcome = BasicRayOutcome<double>;

class Whitted {
 public:
  Whitted(const Scene& scene, ShadingOptions options);
  // The same, the scene's features already known (scene.features() reads every object: 64 processors
  // reading one scene in place would each read its 32,000 objects again).
  Whitted(const Scene& scene, ShadingOptions options, const SceneFeatures& features);

  // Section 3.4: the local term at a hit and the rays it spawns, in the precision of the ray.
  template <class Real>
  void shadeHit(const BasicTracedRay<Real>& ray, const Hit& hit, BasicRayOutcome<Real>& out) const;
  template <class Real>
  void shadeMiss(const BasicTracedRay<Real>& ray, BasicRayOutcome<Real>& out) const;
  // A light ray that found `transmission` (product of T over the objects it crossed, in t order).
  template <class Real>
  void finishLightRay(const BasicTracedRay<Real>& ray, double transmission, BasicRayOutcome<Real>& out) const;

  const Scene& scene() const { return scene_; }
  bool transmissive(std::uint32_t object) const { return transmissionOf(object) > 0; }
  double transmissionOf(std::uint32_t object) const {
    return scene_.materials[scene_.objects[object].material].transmission;
  }
  // The scene has some material with T > 0: light rays must multiply transmissions, not stop at the first
  // hit.
  bool sceneTransmits() const { return sceneTransmits_; }
  int maxDepth() const { return options_.maxDepth; }
  // Some ray may be reflected or refracted: rays other than eye rays reach objects, anywhere, even behind
  // the eye; otherwise only eye rays and their light rays are traced.
  bool spawnsSecondaryRays() const { return spawnsSecondaryRays_; }
  bool worthSpawning(double coeff) const { return coeff * options_.raysPerSample >= options_.minWeight; }

 private:
  // A hit seen from the side the ray arrives on: its normals flipped to face that side.
  template <class Real>
  struct FacingHit {
    Vec3Of<Real> point, geometricNormal, shadingNormal;
    Real t;
    bool entering;
  };
  template <class Real>
  void spawnLightRays(const BasicTracedRay<Real>& ray, const Material& m, const FacingHit<Real>& at,
                      const Vec3Of<Real>& diffuse, BasicRayOutcome<Real>& out) const;
  template <class Real>
  void spawnSecondaryRays(const BasicTracedRay<Real>& ray, const Material& m, const FacingHit<Real>& at,
                          BasicRayOutcome<Real>& out) const;

  const Scene& scene_;
  ShadingOptions options_;
  std::vector<Color> lightIntensity_;
  double ambient_;
  bool sceneTransmits_;
  bool spawnsSecondaryRays_;
};

// Offset a spawned ray's origin off the surface, scale-aware (see kSpawnOffsetRelativeOf).
template <class Real>
Vec3Of<Real> spawnOrigin(const Vec3Of<Real>& point, const Vec3Of<Real>& sideNormal, Real travelled);

}  // namespace raycube::core
