#pragma once
// Every numerical tolerance of the renderer lives here, named, with the reason it exists.
#include <limits>

namespace raycube::core {

// Spawned rays start off the surface by this many units of the hit point's magnitude (max-norm, or the
// distance travelled when larger): a scale-aware offset in the spirit of Wachter & Binder (Ray Tracing
// Gems ch. 6). 2^-32 relative is ~2^20 ulps of double: far above intersection error, far below features.
inline constexpr double kSpawnOffsetRelative = 0x1p-32;

// Bounding boxes are padded by this fraction of their extent (plus the same fraction of their magnitude)
// so that slab tests and the machine's conservative object-to-cell assignment never lose a surface.
inline constexpr double kBoxPaddingRelative = 0x1p-30;

// A direction component smaller than this is treated as parallel to a plane in slab tests' reciprocal.
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace raycube::core

namespace raycube::core {

// The machine assigns objects to regions and cells by their eye-frame boxes widened by this fraction
// (of the coordinate's magnitude, plus one for screen coordinates): conservative against the rounding
// of plane crossings, so a hit always lies in a cell that holds its object.
inline constexpr double kCellMarginRelative = 0x1p-30;

// Every face of a region is a plane through the eye, so a ray that (nearly) passes through the eye meets
// them all at the apex, where z = 0 up to rounding. Crossings with z below this fraction of the ray's
// depth scale are such apex artifacts, not crossings in front of the eye.
inline constexpr double kApexRelative = 0x1p-40;

}  // namespace raycube::core
