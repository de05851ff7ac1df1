#pragma once
// Priol & Bouatouch 3.7.2, deleting the light-ray messages: a processor may trace its light rays where they
// start, against the objects the host found in its light volume (host/prepare/light_volume.h). What the node
// needs of that: the mode, and where its light rays can start.
#include <cstdint>
#include <vector>

#include "core/box.h"
#include "core/vec.h"
#include "node/eye_box.h"

namespace raycube::node {

enum class LightRayMode : std::uint8_t { Messages, Cone, Pyramid };

// Where a processor's light rays can start: a box in the eye frame (x right, y down, z depth) holding every
// point of the region that lies on one of its objects; `corners` are its eight vertices in world space.
// With the paper's cells, also what each light's volume holds, whose cells those light rays walk (3.3):
// per light, its objects (indices into the processor's database) and the eye box of each.
struct LightSources {
  core::Box eyeBox;
  std::vector<core::Vec3> corners;
  std::vector<std::vector<std::uint32_t>> volumeObjects;
  std::vector<std::vector<EyeBox>> volumeBoxes;
};

}  // namespace raycube::node
