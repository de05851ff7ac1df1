#include "core/trace_stats.h"

namespace raycube::core {

const char* rayKindName(RayKind kind) {
  switch (kind) {
    case RayKind::Eye:
      return "eye";
    case RayKind::Reflected:
      return "reflected";
    case RayKind::Refracted:
      return "refracted";
    case RayKind::Light:
      return "light";
  }
  return "?";
}

}  // namespace raycube::core
