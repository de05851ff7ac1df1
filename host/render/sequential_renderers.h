#pragma once
// The two yardsticks of the message-passing machine:
//  - reference: one thread, every object tested for every ray (the ground truth);
//  - image-parallel: the database duplicated in every worker, pixels distributed by oneTBB, a BVH
//    (Roth's approach, which Priol & Bouatouch section 3.7 compare their machine with).
// Both produce bit-identical images: same intersection functions, same tie rule, fixed-point sums.
#include "core/scene.h"
#include "host/machine/render_result.h"
#include "host/machine/render_settings.h"

namespace raycube::host {

RenderResult renderReference(const core::Scene& scene, const RenderSettings& settings);
RenderResult renderImageParallel(const core::Scene& scene, const RenderSettings& settings);

}  // namespace raycube::host
