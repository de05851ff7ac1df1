#pragma once
// The paper's `rayon` message (Priol & Bouatouch 3.5.2): the ray with its original origin and direction,
// where it enters the receiving region (t_enter, the paper's "end" point, and the face), its place in the
// tree (depth, sample, coeff) and, for a light ray, the distance to the light (maxlum = ray.tMax), the light
// term it carries (weight) and the transmission found so far (att).
#include <cstdint>

#include "core/ray.h"

namespace raycube::node {

enum class Face : std::uint8_t { Left = 0, Right = 1, Up = 2, Down = 3 };
inline constexpr int kFaces = 4;

// The face of the neighbour a ray arrives through when it leaves through `face`.
inline Face opposite(Face face) {
  switch (face) {
    case Face::Left:
      return Face::Right;
    case Face::Right:
      return Face::Left;
    case Face::Up:
      return Face::Down;
    case Face::Down:
      return Face::Up;
  }
  return face;
}

// BasicRayMessage::ahead when no hit travels with the ray.
inline constexpr std::uint32_t kNothingAhead = 0xffffffffu;

// Ray state is in the precision Real of the render (--precision): 80 bytes in float, 128 in double. tEnter
// and transmissionOrAheadT stay double: tEnter is where the sender's walk (in double) ended, and the
// reference multiplies transmissions in double, so every chain of processors must too.
template <class Real>
struct BasicRayMessage {
  core::BasicTracedRay<Real> ray;
  double tEnter = 0;  // the ray's interval continues from here in the receiving region
  // One field, two meanings by the ray's kind (the message stays 128 bytes): light rays, the product of T
  // over the objects crossed so far, in t order; closest-hit rays, which have no transmission, the t of the
  // hit of `ahead`.
  double transmissionOrAheadT = 1;
  std::uint16_t destination = 0;  // processor that owns the region the ray enters
  std::uint8_t face = 0;          // face of the receiver it arrives through (statistics)
  // Closest-hit rays: the object whose nearest hit, found by the regions behind beyond their part of the
  // ray, lies nearest (at t = transmissionOrAheadT; infinity: the object has no hit), so a region ahead takes
  // that hit instead of testing the object again (a ray inside a sphere crosses many regions); kNothingAhead:
  // none. A global index, set only where the processors read the host's scene in place. In the padding.
  std::uint32_t ahead = kNothingAhead;
};
using RayMessage = BasicRayMessage<double>;
// The sizes the emulated machine's links charge for (table 2): the carried hit must not grow them.
static_assert(sizeof(BasicRayMessage<double>) == 128 && sizeof(BasicRayMessage<float>) == 80);

}  // namespace raycube::node
