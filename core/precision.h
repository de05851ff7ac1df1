#pragma once
// The arithmetic of ray state and intersection tests, chosen at run time (--precision). The tracer is
// written once over a type Real; the renderers instantiate it for float and double and dispatch here.
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "core/tolerances.h"

namespace raycube::core {

enum class Precision : std::uint8_t { Float, Double };

inline const char* nameOf(Precision precision) {
  return precision == Precision::Float ? "float" : "double";
}

// Calls visit.template operator()<Real>() with Real = float or double.
template <class Visit>
decltype(auto) withPrecision(Precision precision, Visit&& visit) {
  if (precision == Precision::Float) return std::forward<Visit>(visit).template operator()<float>();
  return std::forward<Visit>(visit).template operator()<double>();
}

template <class Real>
inline constexpr Precision kPrecisionOf = sizeof(Real) == sizeof(float) ? Precision::Float
                                                                        : Precision::Double;
template <class Real>
inline constexpr bool kIsFloat = kPrecisionOf<Real> == Precision::Float;

// t in Real, rounded towards direction (+infinity: up, -infinity: down) where Real cannot hold it. A bound
// on t for a traversal in Real must not fall short of the double it stands for: a hit's t rounded to the
// nearest float may lie below a tied hit of another object, whose box then starts beyond the bound and is
// passed over, so the BVH's tie went to the later object where the reference's went to the earlier.
template <class Real>
Real roundedTowards(double t, double direction) {
  const Real r = Real(t);
  return (direction < 0 ? double(r) > t : double(r) < t) ? std::nextafter(r, Real(direction)) : r;
}

// Spawned rays start off the surface by this many units of the hit point's magnitude (max-norm, or the
// distance travelled when larger), in the spirit of Wachter & Binder (Ray Tracing Gems ch. 6): far above the
// intersection error of the precision, far below any feature. Double: 2^-32, about 2^20 ulps. Float: 2^-14,
// about 2^10 ulps (float has too few bits for 2^20 ulps to stay below a feature).
template <class Real>
inline constexpr Real kSpawnOffsetRelativeOf = kIsFloat<Real> ? Real(0x1p-14) : Real(0x1p-32);

// The BVH's box padding for rays of this precision (see kBoxPaddingRelative in core/tolerances.h).
template <class Real>
inline constexpr double kBoxPaddingRelativeOf =
    kIsFloat<Real> ? kFloatBoxPaddingRelative : kBoxPaddingRelative;

// Intersection tests form products of up to three coordinates (the watertight triangle test's scaled t):
// they stay normal and finite for coordinates within [2^-kSafeExponent, 2^kSafeExponent]. A scene outside
// is rescaled by a power of two before tracing (see rescaledFor in core/scene.h).
template <class Real>
inline constexpr int kSafeExponentOf = kIsFloat<Real> ? 8 : 64;

// Largest ratio, as a power of two, between the scene's largest coordinate and its smallest object that
// the precision can render. Double: once the largest coordinate is rescaled to about 1, products of three
// of the smallest object's lengths must stay normal (2^-1022; a third of it, less a margin); beyond, every
// object but the farthest underflows to nothing. Float runs out of bits first: a float t far from its
// origin cannot place a hit on a small object within that object's cells (kFloatHitErrorRelative), and the
// machine and the reference part ways from about 2^30 (measured: a unit sphere inside one of radius 1e9).
template <class Real>
inline constexpr int kMaxSpanExponentOf = kIsFloat<Real> ? 28 : 330;

}  // namespace raycube::core
