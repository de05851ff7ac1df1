#pragma once
// Priol & Bouatouch 3.7.2, deleting the light-ray messages: each processor receives, per light, the objects
// its light rays can meet, so it traces every light ray where it starts. The light volume of a region is
// bounded by a light cone (figure 12) or, more tightly, by the light pyramid of figure 13.
#include <cstdint>
#include <vector>

#include "core/box.h"
#include "core/scene.h"
#include "node/box_tree.h"

namespace raycube::node {

enum class LightRayMode : std::uint8_t { Messages, Cone, Pyramid };

// Where a processor's light rays can start: a box in the eye frame (x right, y down, z depth) holding every
// point of the region that lies on one of its objects; `corners` are its eight vertices in world space.
struct LightSources {
  core::Box eyeBox;
  std::vector<core::Vec3> corners;
};

// Objects (indices into `objects`, a tree of the scene's world boxes widened by kCellMarginRelative, in
// ascending order) the segments from any point of `sources` to `light` may meet. Conservative; every object
// when the light lies among the sources (the volume degenerates).
std::vector<std::uint32_t> objectsInLightVolume(LightRayMode mode, const core::Vec3& light,
                                                const LightSources& sources, const BoxTree& objects);

}  // namespace raycube::node
