#pragma once
// What the user asked for, shared by every rendering mode.
#include <cstdint>

#include "core/precision.h"
#include "core/view.h"
#include "core/whitted.h"

namespace raycube::host {

enum class RenderMode : std::uint8_t { Reference, ImageParallel, Machine };

struct RenderSettings {
  int width = 512;
  int height = 512;
  core::Sampling sampling = core::Sampling::Centers;
  core::ShadingOptions shading;
  core::Precision precision = core::Precision::Double;  // of ray state and intersection arithmetic
  int threads = 0;                                      // image-parallel workers; 0 = all hardware threads
  bool progress = true;
};

}  // namespace raycube::host
