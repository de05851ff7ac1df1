#pragma once
// Every numerical tolerance of the renderer lives here, named, with the reason it exists. Those that depend
// on the precision of the ray arithmetic are in core/precision.h.
#include <limits>

namespace raycube::core {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Bounding boxes are padded by this fraction of their extent (plus the same fraction of their magnitude)
// so that slab tests and the machine's conservative object-to-cell assignment never lose a surface. It is
// sized for float ray arithmetic (2^8 float ulps), whose hits may lie that far off the exact surface; in
// double it only costs a few more candidate tests.
inline constexpr double kBoxPaddingRelative = 0x1p-16;

// The machine assigns objects to regions and cells by their eye-frame boxes widened by this fraction
// (of the coordinate's magnitude, plus one for screen coordinates): conservative against the rounding
// of plane crossings and of float hits, so a hit always lies in a cell that holds its object.
inline constexpr double kCellMarginRelative = 0x1p-16;

// Every face of a region is a plane through the eye, so a ray that (nearly) passes through the eye meets
// them all at the apex, where z = 0 up to rounding. Crossings with z below this fraction of the ray's
// depth scale are such apex artifacts, not crossings in front of the eye.
inline constexpr double kApexRelative = 0x1p-40;

}  // namespace raycube::core
