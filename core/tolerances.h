#pragma once
// Every numerical tolerance of the renderer lives here, named, with the reason it exists. Those that depend
// on the precision of the ray arithmetic are in core/precision.h.
#include <limits>

namespace raycube::core {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Bounding boxes are padded by a fraction of their extent (plus the same fraction of their magnitude) so
// that slab tests never lose a surface: 2^-30 (2^22 ulps) for double rays, 2^-16 (2^8 ulps) for float rays,
// whose hits may lie that far off the exact surface (kBoxPaddingRelativeOf in core/precision.h). Padding
// double's boxes by float's margin would make the image-parallel BVH test many more objects for nothing.
inline constexpr double kBoxPaddingRelative = 0x1p-30;
inline constexpr double kFloatBoxPaddingRelative = 0x1p-16;

// The machine assigns objects to regions, cells and light volumes by their boxes widened by this fraction
// (of the coordinate's magnitude, plus one for screen coordinates): conservative against the rounding
// of plane crossings and of float hits, so a hit always lies in a cell that holds its object. These
// structures serve both precisions, so the margin is float's.
inline constexpr double kCellMarginRelative = 0x1p-16;

// A float ray's t carries 24 bits however near its hit: one reflected from a sphere of radius 6e7 meets a
// unit-size object with t ~ 6e7, whose ulp is 4, so its hit may lie units away from the object, outside
// the object's cells. Cells therefore also widen every object by this fraction (2^2 float ulps) of the
// longest segment in the scene (twice its largest coordinate); for scenes of one scale it is negligible.
inline constexpr double kFloatHitErrorRelative = 0x1p-22;

// Every face of a region is a plane through the eye, so a ray that (nearly) passes through the eye meets
// them all at the apex, where z = 0 up to rounding. Crossings with z below this fraction of the ray's
// depth scale are such apex artifacts, not crossings in front of the eye.
inline constexpr double kApexRelative = 0x1p-40;

// A region's part of a ray is computed by the region itself when the ray gets there (RegionCells): a ray
// leaving its region tests the box of each region ahead (node/regions_ahead.h) over that region's part
// widened by this much of the part's reach, so that a hit a region's rounding would put on the other side
// of a face is still in an interval tested.
inline constexpr double kPartWideningRelative = 1e-9;

}  // namespace raycube::core
