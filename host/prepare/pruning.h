#pragma once
// Priol & Bouatouch 3.2 step 1 and 3.7.2: what the host gives each processor before the synthesis: the
// objects that touch its region and those its light rays can meet, in a database of its own (or shared with
// the processors holding the same objects), and where the scene and each region's objects lie.
#include <cstdint>
#include <vector>

#include "core/box.h"
#include "core/scene.h"
#include "core/view.h"
#include "core/whitted.h"
#include "host/machine/machine_settings.h"
#include "host/prepare/box_tree.h"
#include "node/eye_box.h"
#include "node/logical_processor.h"
#include "node/region_map.h"

namespace raycube::host {

// The processors' setups, and where each region's objects lie where the world boxes are given.
struct PrunedDatabase {
  std::vector<node::NodeSetup> setups;
  std::vector<core::Box> regionBounds;
};

// Each object's eye-frame box as a plain box (the box tree's input).
std::vector<core::Box> eyeFrameBoxesOf(const std::vector<node::EyeBox>& boxes);
// Each object's world box, padded as the cells pad them.
std::vector<core::Box> worldBoxesOf(const core::Scene& scene);
// Boxes holding objects' world boxes (padded as the cells pad them), widened for a float ray's hit error
// over the scene's longest segment, as the eye boxes are.
std::vector<core::Box> widenedForFloatHits(std::vector<core::Box> bounds, double sceneExtent);
// Where the scene lies: a few boxes holding every object's world box.
std::vector<core::Box> sceneBoundsOf(const std::vector<core::Box>& worldBoxes, double sceneExtent);

// 3.2 step 1: each processor receives the objects that touch its region; objects reaching behind the eye
// plane go to every processor (see EyeFrameRay: the rear space belongs to all). 3.7.2: with light cones or
// pyramids, also the objects its light rays can meet. worldBoxesForBounds (may be empty): to find where
// each region's objects lie.
PrunedDatabase pruneDatabase(const core::Whitted& shading, const core::View& view,
                             const node::RegionMap& regions, const std::vector<node::EyeBox>& boxes,
                             const BoxTree& inEyeFrame, const BoxTree& inWorld,
                             const std::vector<core::Box>& worldBoxesForBounds,
                             const MachineSettings& machine);

}  // namespace raycube::host
