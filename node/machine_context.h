#pragma once
// The read-only world every processor shares (Priol & Bouatouch 3.2): the scene, the view, the shading
// options, the screen's partition and where each object lies in the eye frame. Values only, so a host can
// send it to a node in another address space (an MPI rank); processors in one address space share one.
#include <memory>
#include <vector>

#include "core/scene.h"
#include "core/view.h"
#include "core/whitted.h"
#include "node/eye_box.h"
#include "node/region_map.h"

namespace raycube::node {

struct MachineContext {
  std::shared_ptr<const core::Scene> scene;
  core::View view;
  core::ShadingOptions shading;
  RegionMap regions;             // owns its screen lines
  std::vector<EyeBox> eyeBoxes;  // per object
  const ScreenLines& lines() const { return regions.lines(); }
};

}  // namespace raycube::node
