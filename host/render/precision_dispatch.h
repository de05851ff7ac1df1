#pragma once
// Every renderer runs the tracer instantiated for the precision the user chose (--precision), on the scene
// as that precision's arithmetic needs it: rescaled by a power of two when its coordinates lie outside the
// precision's safe range (core::rescaledFor), which leaves the picture unchanged.
#include <optional>

#include "core/precision.h"
#include "core/scene.h"
#include "host/machine/render_result.h"

namespace raycube::host {

// Calls render.template operator()<Real>(tracedScene) with Real = float or double.
template <class Render>
RenderResult renderInPrecision(const core::Scene& scene, core::Precision precision, Render&& render) {
  core::requireRenderable(scene, precision);
  const std::optional<core::Scene> rescaled = core::rescaledFor(scene, precision);
  const core::Scene& traced = rescaled ? *rescaled : scene;
  return core::withPrecision(precision,
                             [&]<class Real>() { return render.template operator()<Real>(traced); });
}

}  // namespace raycube::host
