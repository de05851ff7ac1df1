#pragma once
// A ray of the ray tree, carrying everything the paper's `rayon` message carries (section 3.5.2):
// the original origin and direction keep the ray's identity wherever it travels. Ray state is in the
// precision the user chose (Real = float or double); Ray and TracedRay are the double ones.
#include <cstddef>
#include <cstdint>

#include "core/vec.h"

namespace raycube::core {

enum class RayKind : std::uint8_t { Eye = 0, Reflected = 1, Refracted = 2, Light = 3 };
inline constexpr int kRayKinds = 4;

template <class Real>
struct BasicRay {
  Vec3Of<Real> origin{0, 0, 0};
  Vec3Of<Real> direction{0, 0, 1};  // unit length
  Real tMin = 0;                    // eye rays: hither; spawned rays: 0 (their origin is already offset)
  Real tMax = 0;  // light rays: distance to the light (the paper's maxlum); others: infinity

  Vec3Of<Real> at(Real t) const { return origin + t * direction; }

  // The same ray in another precision (rounded to nearest; exact towards double).
  template <class To>
  BasicRay<To> as() const {
    return BasicRay<To>{Vec3Of<To>(origin), Vec3Of<To>(direction), To(tMin), To(tMax)};
  }
};
using Ray = BasicRay<double>;

// A ray with its place in the tree (Priol & Bouatouch 3.4): the cumulated Ks/Kt product `coeff`, and for a
// light ray the light term it will deliver, scaled by the transmission it finds (the paper's att).
template <class Real>
struct BasicTracedRay {
  BasicRay<Real> ray;
  Vec3Of<Real> weight{0, 0, 0};  // light rays only: coeff * light * (diffuse + specular)
  Real coeff = 1;                // cumulated product of Ks and T along the path
  std::uint32_t sample = 0;
  std::uint8_t depth = 1;  // the eye ray has depth 1 (SPD rule 7)
  RayKind kind = RayKind::Eye;
  std::uint16_t light = 0;  // light rays: which light they go to (kMaxLights keeps it exact)
};
using TracedRay = BasicTracedRay<double>;

// A ray names its light in 16 bits (the message stays 128 bytes): scenes with more lights are refused.
inline constexpr std::size_t kMaxLights = std::size_t(1) << 16;

// A piece of a sample's colour: the host adds these up in any order (section 3.4), in double whatever the
// precision of the rays.
struct Contribution {
  std::uint32_t sample = 0;
  Color value{0, 0, 0};
};

}  // namespace raycube::core
