#pragma once
// Priol & Bouatouch 3.7.2, deleting the light-ray messages: each processor receives, per light, the objects
// its light rays can meet, so it traces every light ray where it starts. The light volume of a region is
// bounded by a light cone (figure 12) or, more tightly, by the light pyramid of figure 13. Pruning is the
// host's (3.2 step 1).
#include <cstdint>
#include <vector>

#include "core/vec.h"
#include "host/prepare/box_tree.h"
#include "node/light_sources.h"

namespace raycube::host {

// Objects (indices into `objects`, a tree of the scene's world boxes widened by kCellMarginRelative, in
// ascending order) the segments from any point of `sources` to `light` may meet. Conservative; every object
// when the light lies among the sources (the volume degenerates).
std::vector<std::uint32_t> objectsInLightVolume(node::LightRayMode mode, const core::Vec3& light,
                                                const node::LightSources& sources, const BoxTree& objects);

}  // namespace raycube::host
