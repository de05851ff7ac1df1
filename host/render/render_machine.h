#pragma once
// The message-passing machine (Priol & Bouatouch section 3): the host partitions the screen into pixel
// areas (an R x C grid, 3.1, or a BSP of equal estimated loads, 3.7.1), prunes the database for each region
// (3.2 step 1) and for its light volumes (3.7.2), starts one engine of logical processors, accumulates the
// contributions they send (3.4, 3.5.1) and stops when the token ring has proved termination (3.6).
#include "core/scene.h"
#include "host/machine/machine_report.h"
#include "host/machine/machine_settings.h"
#include "host/machine/render_result.h"
#include "host/machine/render_settings.h"

namespace raycube::host {

RenderResult renderMachine(const core::Scene& scene, const RenderSettings& settings,
                           const MachineSettings& machine, MachineReport* report = nullptr);

}  // namespace raycube::host
