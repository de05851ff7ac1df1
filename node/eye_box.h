#pragma once
// Where an object lies in the eye frame, and whether it can touch a column of screen space between two
// depths: the test behind the host's pruning (3.2 step 1) and the node's cell lists (3.3).
#include "core/scene.h"
#include "core/view.h"

namespace raycube::node {

struct EyeBox {
  core::Vec3 lo, hi;  // eye frame (x right, y down, z depth), widened by kCellMarginRelative
};

// sceneExtent bounds the length of any ray segment in the scene (e.g. twice its largest coordinate): a
// float ray's hit may lie kFloatHitErrorRelative of it off the object, so the box is widened by that too.
EyeBox eyeBoxOf(const core::Object& object, const core::View& view, double sceneExtent);

// Screen-coordinate ranges [lo, hi] of a column, and a depth slab [zLo, zHi] (zLo >= 0).
struct ColumnSlab {
  double sLo, sHi, qLo, qHi, zLo, zHi;
};

// Conservative: true whenever some point of the object's box lies in the slab (up to the margin).
bool mayTouch(const EyeBox& box, const ColumnSlab& slab);

// Objects that reach the eye plane or behind it: every node holds them for rays' rear parts.
bool reachesBehindEye(const EyeBox& box);

}  // namespace raycube::node
